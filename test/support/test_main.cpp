// GoogleTest main for every fcl_quadric test executable. Floating-point traps for invalid
// operations and division by zero are on (Jolt's practice): a NaN produced anywhere in the
// library aborts the test with SIGFPE instead of leaking into a result. Set
// FCL_QUADRIC_NO_FP_TRAPS=1 to switch them off when debugging.
#include <cfenv>
#include <cstdlib>

#include <gtest/gtest.h>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
#if defined(__GLIBC__) && (defined(__x86_64__) || defined(__i386__))
  const char* off = std::getenv("FCL_QUADRIC_NO_FP_TRAPS");
  if (off == nullptr || off[0] == '0') feenableexcept(FE_INVALID | FE_DIVBYZERO);
#endif
  return RUN_ALL_TESTS();
}
