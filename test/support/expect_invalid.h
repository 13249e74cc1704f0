#pragma once
/// The tests' one check of a documented error: f must throw std::invalid_argument whose message
/// contains `needle` (the empty string accepts any message).
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace fcl_quadric {
namespace test {

template <typename F>
void expectInvalid(F f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no exception, expected one containing '" << needle << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << "expected '" << needle << "' in: " << e.what();
  }
}

}  // namespace test
}  // namespace fcl_quadric
