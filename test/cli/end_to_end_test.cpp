// End-to-end tests: run the built fcl_quadric executable on temporary files and check exit status,
// stdout and stderr against the library called directly. The executable is $FCL_QUADRIC_EXE, which
// ctest sets to the build tree's own program (test/CMakeLists.txt), else the path compiled in.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <set>
#include <sstream>

#include <cairo.h>
#include <nlohmann/json.hpp>

#include "cli/bad_scenes.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/signed_distance.h"
#include "fcl_quadric/version.h"

namespace fcl_quadric {
namespace cli {
namespace {

using nlohmann::json;

struct ProcessResult {
  int status = -1;  // exit status, or -1 if the process did not exit normally
  std::string out;
  std::string err;
};

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::size_t countLines(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

class EndToEnd : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    std::string pattern = (std::filesystem::temp_directory_path() / "fcl_quadric_cli_test.XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }

  /// Writes `text` to a file in the temporary directory and returns its path.
  static std::string writeFile(const std::string& name, const std::string& text) {
    const std::filesystem::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }

  /// Runs the executable with `args`, capturing stdout and stderr.
  static ProcessResult run(const std::vector<std::string>& args) {
    const std::filesystem::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    const char* exe = std::getenv("FCL_QUADRIC_EXE");
    std::string command = shellQuote(exe != nullptr && *exe != '\0' ? exe : FCL_QUADRIC_EXE);
    for (const std::string& a : args) command += " " + shellQuote(a);
    command += " >" + shellQuote(out.string()) + " 2>" + shellQuote(err.string()) + " </dev/null";
    const int raw = std::system(command.c_str());
    ProcessResult r;
    if (raw != -1 && WIFEXITED(raw)) r.status = WEXITSTATUS(raw);
    r.out = readFile(out);
    r.err = readFile(err);
    return r;
  }

  /// Checks the error contract: status 2, nothing on stdout, one "fcl_quadric: error: " line
  /// on stderr containing `fragment`.
  static void expectUsageOrInputError(const ProcessResult& r, const std::string& fragment) {
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(countLines(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("fcl_quadric: error: ", 0), 0u) << r.err;
    EXPECT_FALSE(r.err.empty() || r.err.back() != '\n') << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << "expected '" << fragment << "' in: " << r.err;
  }

  static inline std::filesystem::path dir_;
};

Eigen::Vector3d vec(const json& j) { return Eigen::Vector3d(j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()); }

/// Properties every reported pair must have, whatever computed it.
void expectConsistentPair(const json& p) {
  const std::string status = p.at("status").get<std::string>();
  const double d = p.at("signed_distance").get<double>();
  const Eigen::Vector3d pa = vec(p.at("points").at(0)), pb = vec(p.at("points").at(1)), n = vec(p.at("normal"));
  EXPECT_TRUE(status == "separate" || status == "touching" || status == "overlapping") << status;
  EXPECT_EQ(p.at("collide").get<bool>(), status != "separate");
  EXPECT_NEAR(n.norm(), 1.0, 1e-12);
  if (status == "separate") {
    EXPECT_GT(d, 0.0);
    EXPECT_NEAR((pb - pa).norm(), d, 1e-9 * (1.0 + d));
    EXPECT_NEAR((pb - pa).dot(n), d, 1e-9 * (1.0 + d));  // the normal points from a to b
  } else if (status == "overlapping") {
    EXPECT_LT(d, 0.0);
    EXPECT_NEAR((pa - pb).dot(n), -d, 1e-6 * (1.0 + std::abs(d)));  // depth along the normal
  }
}

TEST_F(EndToEnd, CheckExampleSceneAgreesWithLibrary) {
  const std::string path = std::string(FCL_QUADRIC_SOURCE_DIR) + "/examples/scene_basic.json";
  const ProcessResult r = run({"check", path});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const json output = json::parse(r.out);
  const json scene = json::parse(readFile(path));

  // Build the library's objects straight from the scene JSON (independently of the CLI's reader).
  auto pose = [&](const std::string& name) {
    for (const json& o : scene.at("objects")) {
      if (o.at("name") != name) continue;
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      const json pose = o.value("pose", json::object());
      if (pose.contains("translation")) X.translation() = vec(pose.at("translation"));
      if (pose.contains("quaternion")) {
        const json& q = pose.at("quaternion");
        X.linear() = Eigen::Quaterniond(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>())
                         .normalized().toRotationMatrix();
      }
      return std::make_pair(o.at("shape"), X);
    }
    ADD_FAILURE() << "no object " << name;
    return std::make_pair(json(), Eigen::Isometry3d::Identity());
  };
  auto ellipsoid = [&](const std::string& name) {
    const auto [shape, X] = pose(name);
    const Eigen::Vector3d radii = shape.at("type") == "sphere" ? Eigen::Vector3d::Constant(shape.at("radius").get<double>())
                                                               : vec(shape.at("radii"));
    return Ellipsoid(radii, X);
  };

  const json& pairs = output.at("pairs");
  ASSERT_EQ(pairs.size(), scene.at("pairs").size());
  std::map<std::string, std::string> statuses;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const json& p = pairs[k];
    SCOPED_TRACE(p.dump());
    EXPECT_EQ(p.at("a"), scene.at("pairs")[k][0]);
    EXPECT_EQ(p.at("b"), scene.at("pairs")[k][1]);
    expectConsistentPair(p);
    const std::string a = p.at("a"), b = p.at("b");
    statuses[a + "-" + b] = p.at("status");
    const bool box_a = pose(a).first.at("type") == "box", box_b = pose(b).first.at("type") == "box";
    EXPECT_EQ(p.at("method"), box_a && box_b ? "fcl" : "exact");
    if (box_a || box_b) continue;  // ellipsoid-box pairs: test/cli/commands_test.cpp
    const Ellipsoid ea = ellipsoid(a), eb = ellipsoid(b);
    EXPECT_EQ(p.at("status"), toString(classifyEllipsoids(ea, eb).status));
    const SignedDistanceResult sd = signedDistance(ea, eb);
    EXPECT_NEAR(p.at("signed_distance").get<double>(), sd.distance, 1e-12);
    EXPECT_LT((vec(p.at("points")[0]) - sd.point_a).norm(), 1e-12);
    EXPECT_LT((vec(p.at("points")[1]) - sd.point_b).norm(), 1e-12);
    EXPECT_LT((vec(p.at("normal")) - sd.normal).norm(), 1e-12);
    EXPECT_NEAR(ea.implicit(vec(p.at("points")[0])), 0.0, 1e-9);
    EXPECT_NEAR(eb.implicit(vec(p.at("points")[1])), 0.0, 1e-9);
  }
  // The configurations the example was built to show (see examples/README.md).
  EXPECT_EQ(statuses["A-B"], "overlapping");
  EXPECT_EQ(statuses["A-C"], "separate");
  EXPECT_EQ(statuses["A-ball"], "touching");
  EXPECT_EQ(statuses["A-crate"], "separate");

  // ball-crate against the closed form: distance from the sphere centre to the box, minus r.
  for (const json& p : pairs) {
    if (p.at("a") != "ball" || p.at("b") != "crate") continue;
    const auto [ball, X_ball] = pose("ball");
    const auto [crate, X_crate] = pose("crate");
    const Eigen::Vector3d c = X_crate.inverse() * X_ball.translation();
    const Eigen::Vector3d half = 0.5 * vec(crate.at("size"));
    const Eigen::Vector3d nearest = c.cwiseMax(-half).cwiseMin(half);
    const double expected = (c - nearest).norm() - ball.at("radius").get<double>();
    EXPECT_NEAR(p.at("signed_distance").get<double>(), expected, 1e-6);
    EXPECT_LT((vec(p.at("points")[1]) - X_crate * nearest).norm(), 1e-5);
  }
}

TEST_F(EndToEnd, CheckRandomEllipsoidSceneMatchesLibraryPairByPair) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> radius(0.4, 1.6), position(-1.5, 1.5);
  std::normal_distribution<double> normal(0.0, 1.0);
  json objects = json::array();
  std::vector<Ellipsoid> ellipsoids;
  for (int i = 0; i < 12; ++i) {
    const Eigen::Vector3d r(radius(rng), radius(rng), radius(rng));
    const Eigen::Vector3d p(position(rng), position(rng), position(rng));
    const Eigen::Quaterniond q = Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
    const bool sphere = i % 4 == 3;
    json shape = sphere ? json{{"type", "sphere"}, {"radius", r[0]}} : json{{"type", "ellipsoid"}, {"radii", {r[0], r[1], r[2]}}};
    objects.push_back({{"name", "obj" + std::to_string(i)},
                       {"shape", shape},
                       {"pose", {{"translation", {p[0], p[1], p[2]}}, {"quaternion", {q.w(), q.x(), q.y(), q.z()}}}}});
    ellipsoids.emplace_back(sphere ? Eigen::Vector3d::Constant(r[0]) : r, q.toRotationMatrix(), p);
  }
  const std::string path = writeFile("random.json", json{{"objects", objects}}.dump());
  const ProcessResult r = run({"check", path});
  ASSERT_EQ(r.status, 0) << r.err;
  const json pairs = json::parse(r.out).at("pairs");
  ASSERT_EQ(pairs.size(), 66u);  // all unordered pairs of 12
  std::size_t k = 0, separate = 0;
  for (std::size_t i = 0; i < ellipsoids.size(); ++i) {
    for (std::size_t j = i + 1; j < ellipsoids.size(); ++j, ++k) {
      const json& p = pairs[k];
      SCOPED_TRACE(p.dump());
      EXPECT_EQ(p.at("a"), "obj" + std::to_string(i));
      EXPECT_EQ(p.at("b"), "obj" + std::to_string(j));
      expectConsistentPair(p);
      const Separation s = classifyEllipsoids(ellipsoids[i], ellipsoids[j]).status;
      EXPECT_EQ(p.at("status"), toString(s));
      const SignedDistanceResult sd = signedDistance(ellipsoids[i], ellipsoids[j]);
      // The file stores the inputs to 17 digits, so the results agree to rounding.
      EXPECT_NEAR(p.at("signed_distance").get<double>(), sd.distance, 1e-9);
      EXPECT_LT((vec(p.at("points")[0]) - sd.point_a).norm(), 1e-6);
      EXPECT_LT((vec(p.at("points")[1]) - sd.point_b).norm(), 1e-6);
      EXPECT_EQ(p.at("method"), "exact");
      separate += s == Separation::Separated;
    }
  }
  ::testing::Test::RecordProperty("separate_pairs", static_cast<int>(separate));
  // Both outcomes occur, or the comparison proves little.
  EXPECT_GT(separate, 15u);
  EXPECT_LT(separate, 55u);
}

TEST_F(EndToEnd, CheckSceneWithoutPairsPrintsEmptyList) {
  const ProcessResult r = run({"check", writeFile("single.json", R"({"objects":[{"name":"solo","shape":{"type":"sphere","radius":1}}]})")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json::parse(r.out), json::parse(R"({"pairs":[]})"));
}

TEST_F(EndToEnd, EveryBadSceneExitsTwoWithOneLineNamingThePointer) {
  int index = 0;
  for (const test::BadScene& c : test::badScenes()) {
    SCOPED_TRACE(c.name);
    const std::string path = writeFile("bad" + std::to_string(index++) + ".json", c.text);
    const ProcessResult r = run({"check", path});
    expectUsageOrInputError(r, c.message);
    if (!c.pointer.empty()) {
      EXPECT_EQ(r.err.rfind("fcl_quadric: error: " + c.pointer + ": ", 0), 0u) << r.err;
    }
    if (c.pointer.empty()) {
      EXPECT_NE(r.err.find(path), std::string::npos) << r.err;  // names the file
    }
  }
}

TEST_F(EndToEnd, ErrorLineHasTheDocumentedFormat) {
  const std::string text = R"({"objects":[)" + test::sphereAt("A", 0) + "," + test::sphereAt("B", 3) +
                           R"(,{"name":"C","shape":{"type":"ellipsoid","radii":[1,-1,1]}}]})";
  const ProcessResult r = run({"check", writeFile("documented.json", text)});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "fcl_quadric: error: /objects/2/shape/radii/1: radius must be finite and > 0, got -1\n");
}

TEST_F(EndToEnd, MalformedJsonReportsParsePosition) {
  const ProcessResult r = run({"check", writeFile("malformed.json", "{\n  \"objects\": [\n    {\"name\": \"A\" \"shape\": 1}\n  ]\n}\n")});
  expectUsageOrInputError(r, "malformed JSON: parse error at line 3, column");
}

TEST_F(EndToEnd, UnreadableFilesExitTwo) {
  expectUsageOrInputError(run({"check", (dir_ / "does_not_exist.json").string()}), "No such file or directory");
  expectUsageOrInputError(run({"check", dir_.string()}), "Is a directory");
}

TEST_F(EndToEnd, ControlCharactersCannotBreakTheOneLineContract) {
  // A duplicate name containing a newline, and a file name containing one.
  const std::string text = R"({"objects":[{"name":"x\ny","shape":{"type":"sphere","radius":1}},)"
                           R"({"name":"x\ny","shape":{"type":"sphere","radius":1}}]})";
  expectUsageOrInputError(run({"check", writeFile("dup.json", text)}), "/objects/1/name: duplicate object name");
  expectUsageOrInputError(run({"check", (dir_ / "line\nbreak.json").string()}), "cannot open scene file");
}

TEST_F(EndToEnd, VersionAndHelp) {
  ProcessResult r = run({"--version"});
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out, std::string("fcl_quadric ") + FCL_QUADRIC_VERSION_STRING + "\n");
  EXPECT_EQ(r.err, "");
  r = run({"--help"});
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("check"), std::string::npos);
  EXPECT_NE(r.out.find("demo"), std::string::npos);
  EXPECT_NE(r.out.find("--version"), std::string::npos);
  r = run({"demo", "--help"});
  EXPECT_EQ(r.status, 0);
  for (const char* option : {"--frames", "--objects", "--seed"}) EXPECT_NE(r.out.find(option), std::string::npos) << option;
  r = run({"check", "--help"});
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("SCENE"), std::string::npos);
}

TEST_F(EndToEnd, UsageErrorsExitTwoWithOneLine) {
  expectUsageOrInputError(run({}), "subcommand is required");
  expectUsageOrInputError(run({"frobnicate"}), "subcommand is required");
  expectUsageOrInputError(run({"check"}), "SCENE is required");
  expectUsageOrInputError(run({"check", "a.json", "b.json"}), "b.json");
  expectUsageOrInputError(run({"demo", "--frames", "0"}), "--frames");
  expectUsageOrInputError(run({"demo", "--objects", "many"}), "--objects");
  expectUsageOrInputError(run({"demo", "--bogus"}), "--bogus");
  expectUsageOrInputError(run({"demo", "--seed", "-1"}), "--seed");
  expectUsageOrInputError(run({"demo", "--seed", "18446744073709551616"}), "--seed");  // 2^64
  expectUsageOrInputError(run({"check", "a.json", "demo"}), "");  // one subcommand only
}

/// The integer after `label` in the demo summary (fails if absent).
std::uint64_t summaryNumber(const std::string& text, const std::string& label) {
  const std::regex re(label + R"(\s*([0-9]+))");
  std::smatch m;
  if (!std::regex_search(text, m, re)) {
    ADD_FAILURE() << "no '" << label << "' in:\n" << text;
    return 0;
  }
  return std::stoull(m[1].str());
}

TEST_F(EndToEnd, DemoPrintsConsistentSummary) {
  const ProcessResult r = run({"demo", "--frames", "50", "--objects", "10"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("10 spinning, drifting ellipsoids in a box, 50 frames (seed 1)"), std::string::npos) << r.out;
  const std::uint64_t tests = summaryNumber(r.out, "pair tests \\(bounding spheres overlap\\):");
  EXPECT_NE(r.out.find(std::to_string(tests) + " of 2250 pair-frames"), std::string::npos) << r.out;  // 50 x 45
  const std::uint64_t colliding = summaryNumber(r.out, "colliding pair-frames:");
  const std::uint64_t separated = summaryNumber(r.out, "separations:");
  const std::uint64_t plane_hits = summaryNumber(r.out, "separations:\\s*[0-9]+, of which");
  EXPECT_GT(tests, 0u);
  EXPECT_EQ(colliding + separated, tests);
  EXPECT_LE(plane_hits, separated);
  EXPECT_NE(r.out.find("coherent and direct answers agree on all " + std::to_string(tests) + " pair tests"),
            std::string::npos);
  for (const char* line : {"mean time per pair test, coherence:", "mean time per pair test, direct:", "speed-up from coherence:"}) {
    EXPECT_NE(r.out.find(line), std::string::npos) << line;
  }
  // Same seed, same simulation (timings aside); another seed, another scene.
  const ProcessResult again = run({"demo", "--frames", "50", "--objects", "10"});
  EXPECT_EQ(summaryNumber(again.out, "colliding pair-frames:"), colliding);
  EXPECT_EQ(summaryNumber(again.out, "separations:"), separated);
  const ProcessResult other = run({"demo", "--frames", "50", "--objects", "10", "--seed", "12345"});
  ASSERT_EQ(other.status, 0) << other.err;
  EXPECT_NE(other.out.find("(seed 12345)"), std::string::npos);
}

// `fcl_quadric bench --size tiny`: runs once for the whole group (it takes seconds). Timings are
// not asserted, only that every experiment and peer reports a finite positive time and that the
// charts are valid PNGs.
class BenchEndToEnd : public EndToEnd {
 protected:
  static const ProcessResult& tiny() {
    static const ProcessResult r = run({"bench", "--size", "tiny", "--out", (dir_ / "bench_tiny").string()});
    return r;
  }
};

TEST_F(BenchEndToEnd, TinyWritesResultsForEveryExperimentAndPeer) {
  const ProcessResult& r = tiny();
  ASSERT_EQ(r.status, 0) << r.err;
  const json doc = json::parse(readFile(dir_ / "bench_tiny" / "bench.json"));
  const std::vector<std::string> experiments = {"random", "near_tangent", "separating_planes", "boxing",
                                                "arm",    "broadphase",   "octree",            "quadric_shapes"};
  ASSERT_EQ(doc.at("experiments").size(), experiments.size());
  for (std::size_t i = 0; i < experiments.size(); ++i) {
    const json& e = doc.at("experiments").at(i);
    EXPECT_EQ(e.at("name"), experiments[i]);
    EXPECT_NE(r.out.find("== " + experiments[i] + ": "), std::string::npos) << "no table for " << experiments[i];
    std::set<std::string> peers;
    for (const json& row : doc.at("results")) {
      if (row.at("experiment") != experiments[i]) continue;
      peers.insert(row.at("peer").get<std::string>());
      const double ns = row.at("ns_per_query").get<double>();
      EXPECT_TRUE(std::isfinite(ns) && ns > 0.0) << row.dump();
      EXPECT_GT(row.at("n").get<std::size_t>(), 0u) << row.dump();
      EXPECT_TRUE(std::isfinite(row.at("ratio").get<double>()) && row.at("ratio").get<double>() > 0.0) << row.dump();
      EXPECT_TRUE(row.at("wrong").is_null() || row.at("wrong").get<long>() >= 0) << row.dump();
      // fcl_quadric is the exact answer of every experiment but near_tangent (truth by construction);
      // the CSG rows have no peer and no independent answer in the run (not counted).
      if (row.at("peer") == "fcl_quadric" && experiments[i] != "near_tangent") {
        if (row.at("case") == "csg ring-wedge") {
          EXPECT_TRUE(row.at("wrong").is_null()) << row.dump();
        } else {
          EXPECT_EQ(row.at("wrong"), 0) << row.dump();
        }
      }
    }
    EXPECT_EQ(peers.count("fcl_quadric"), 1u) << experiments[i];
    EXPECT_GE(peers.size(), 2u) << experiments[i];
    if (experiments[i] != "octree") {  // Bullet has no voxel-map shape
      EXPECT_EQ(peers.count("bullet"), 1u) << experiments[i];
    }
    // The chart parses back as a PNG of nonzero size.
    const std::string png = (dir_ / "bench_tiny" / e.at("chart").get<std::string>()).string();
    cairo_surface_t* image = cairo_image_surface_create_from_png(png.c_str());
    EXPECT_EQ(cairo_surface_status(image), CAIRO_STATUS_SUCCESS) << png;
    EXPECT_GT(cairo_image_surface_get_width(image), 0) << png;
    EXPECT_GT(cairo_image_surface_get_height(image), 0) << png;
    cairo_surface_destroy(image);
  }
}

TEST_F(BenchEndToEnd, BadSizeIsAUsageError) {
  expectUsageOrInputError(run({"bench", "--size", "huge", "--out", (dir_ / "bench_bad").string()}), "huge");
}

TEST_F(BenchEndToEnd, UnknownExperimentIsAUsageError) {
  expectUsageOrInputError(run({"bench", "--only", "random,nonesuch", "--out", (dir_ / "bench_bad").string()}),
                          "nonesuch");
}

TEST_F(BenchEndToEnd, UnwritableOutIsAnInputError) {
  // A regular file where the directory should be.
  const std::string file = writeFile("not_a_directory", "x");
  expectUsageOrInputError(run({"bench", "--size", "tiny", "--only", "random", "--out", file}), "not_a_directory");
}

}  // namespace
}  // namespace cli
}  // namespace fcl_quadric
