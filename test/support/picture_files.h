#pragma once
// Reading the CLI's pictures back, without Google Test (shared by test/cli/picture_check.h and
// the fuzz target fuzz_scene): run the CLI in-process, scratch directories, an XML
// well-formedness check for SVG, Cairo's PNG reader for PNG.

#include <cairo.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "fcl_quadric/cli.h"

namespace fcl_quadric {
namespace cli {
namespace test {

namespace fs = std::filesystem;

struct RunResult {
  int status;
  std::string out;
  std::string err;
};

inline RunResult runCli(const std::vector<std::string>& args) {
  std::vector<const char*> argv{"fcl_quadric"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  const int status = run(static_cast<int>(argv.size()), argv.data(), out, err);
  return {status, out.str(), err.str()};
}

/// A fresh empty directory for one test's outputs.
inline fs::path scratchDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("fcl_quadric_cli_pictures_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A minimal XML well-formedness check: a prolog "<?xml", then elements that nest and close
/// properly (attribute values may contain '>'), comments / processing instructions / declarations
/// skipped, exactly one root element, named `root`. Returns "" when well-formed, else the problem.
inline std::string xmlProblem(const std::string& text, const std::string& root) {
  if (text.rfind("<?xml", 0) != 0) return "does not start with <?xml";
  std::vector<std::string> stack;
  int roots = 0;
  std::size_t i = 0;
  while (true) {
    const std::size_t lt = text.find('<', i);
    if (lt == std::string::npos) break;
    if (text.compare(lt, 4, "<!--") == 0) {
      const std::size_t end = text.find("-->", lt + 4);
      if (end == std::string::npos) return "unterminated comment";
      i = end + 3;
      continue;
    }
    if (text.compare(lt, 2, "<?") == 0 || text.compare(lt, 2, "<!") == 0) {
      const std::size_t end = text.find('>', lt);
      if (end == std::string::npos) return "unterminated declaration";
      i = end + 1;
      continue;
    }
    // A tag: find its end outside quoted attribute values.
    std::size_t j = lt + 1;
    char quote = 0;
    for (; j < text.size(); ++j) {
      const char c = text[j];
      if (quote) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '>') {
        break;
      } else if (c == '<') {
        return "'<' inside a tag at offset " + std::to_string(j);
      }
    }
    if (j >= text.size()) return "unterminated tag at offset " + std::to_string(lt);
    const std::string tag = text.substr(lt + 1, j - lt - 1);
    i = j + 1;
    if (tag.empty()) return "empty tag";
    if (tag[0] == '/') {
      const std::string name = tag.substr(1, tag.find_first_of(" \t\r\n", 1) - 1);
      if (stack.empty() || stack.back() != name) return "mismatched </" + name + ">";
      stack.pop_back();
      continue;
    }
    const std::string name = tag.substr(0, tag.find_first_of(" \t\r\n/"));
    if (name.empty()) return "element without a name";
    if (stack.empty()) {
      if (++roots > 1) return "more than one root element";
      if (name != root) return "root element is <" + name + ">";
    }
    if (tag.back() != '/') stack.push_back(name);
  }
  if (roots != 1) return "no root element";
  if (!stack.empty()) return "unclosed <" + stack.back() + ">";
  return "";
}

/// The PNG read back by Cairo (owned; destroy with cairo_surface_destroy).
inline cairo_surface_t* readPng(const fs::path& path) { return cairo_image_surface_create_from_png(path.c_str()); }

/// The pixel (r, g, b) in 0..255 at (x, y) of an ARGB32/RGB24 image surface.
inline std::array<int, 3> pixel(cairo_surface_t* image, int x, int y) {
  cairo_surface_flush(image);
  const unsigned char* data = cairo_image_surface_get_data(image);
  const int stride = cairo_image_surface_get_stride(image);
  std::uint32_t v;
  std::memcpy(&v, data + y * stride + 4 * x, 4);  // native-endian 0xAARRGGBB
  return {static_cast<int>((v >> 16) & 0xff), static_cast<int>((v >> 8) & 0xff), static_cast<int>(v & 0xff)};
}

/// Fraction of pixels that are not (nearly) white: a blank picture would be ~0.
inline double inkFraction(cairo_surface_t* image) {
  const int w = cairo_image_surface_get_width(image), h = cairo_image_surface_get_height(image);
  long ink = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const auto p = pixel(image, x, y);
      ink += (p[0] < 235 || p[1] < 235 || p[2] < 235);
    }
  }
  return static_cast<double>(ink) / (static_cast<double>(w) * h);
}

}  // namespace test
}  // namespace cli
}  // namespace fcl_quadric
