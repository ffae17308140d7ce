// The README's code examples are compiled by tests that hold a copy of each
// example between "// --- README <name>example begins ---" and "... ends ---"
// markers. This test keeps the copies honest: every marked block, with its
// common indentation removed, must appear in README.md as consecutive lines
// of one code block (which may itself be indented, e.g. inside a list item).
// An API change that makes a test edit its example therefore fails here
// until the README shows the same code.
#include <catch2/catch.hpp>

#include <cstddef>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../readme_quote.h"

namespace {

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

size_t indent_of(const std::string& line) { return line.find_first_not_of(' '); }

/// Lines with their common leading spaces removed (blank lines ignored for
/// the common indent and kept empty).
std::vector<std::string> dedent(const std::vector<std::string>& lines) {
  size_t common = std::string::npos;
  for (const std::string& l : lines) {
    const size_t i = indent_of(l);
    if (i != std::string::npos && i < common) common = i;
  }
  std::vector<std::string> out;
  for (const std::string& l : lines) out.push_back(indent_of(l) == std::string::npos ? std::string{} : l.substr(common));
  return out;
}

struct Block {
  std::string name;
  std::vector<std::string> lines;
};

/// The marked blocks of one test source.
std::vector<Block> marked_blocks(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in.good());
  std::ostringstream s;
  s << in.rdbuf();
  const std::vector<std::string> lines = split_lines(s.str());
  std::vector<Block> blocks;
  const std::string begin = "// --- README ", begins = "example begins ---";
  for (size_t i = 0; i < lines.size(); ++i) {
    const size_t b = lines[i].find(begin), e = lines[i].find(begins);
    // A marker is a line of its own (not, say, a string literal naming it).
    if (b == std::string::npos || e == std::string::npos || indent_of(lines[i]) != b) continue;
    Block block{lines[i].substr(b + begin.size(), e - b - begin.size()) + "example", {}};
    const std::string end = "// --- README " + lines[i].substr(b + begin.size(), e - b - begin.size()) + "example ends ---";
    size_t j = i + 1;
    for (; j < lines.size() && lines[j].find(end) == std::string::npos; ++j) block.lines.push_back(lines[j]);
    INFO(path << ": " << block.name << " has no end marker");
    REQUIRE(j < lines.size());
    block.lines = dedent(block.lines);
    blocks.push_back(block);
    i = j;
  }
  return blocks;
}

/// True when `block` appears as consecutive lines of README.md, all with the
/// same extra indentation.
bool readme_contains(const std::vector<std::string>& readme, const std::vector<std::string>& block) {
  if (block.empty()) return true;
  for (size_t start = 0; start + block.size() <= readme.size(); ++start) {
    const size_t at = readme[start].find(block[0]);
    if (block[0].empty() || at == std::string::npos || indent_of(readme[start]) != at) continue;
    const std::string pad(at, ' ');
    bool all = true;
    for (size_t k = 0; k < block.size() && all; ++k)
      all = block[k].empty() ? indent_of(readme[start + k]) == std::string::npos : readme[start + k] == pad + block[k];
    if (all) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("every README example compiled by a test appears in README.md as written", "[replay][readme]") {
  const std::string root = TANDEM_SESSION_SOURCE_DIR;
  const std::vector<std::string> sources = {
      root + "/tests/physics/test_readme_example.cpp",
      root + "/tests/physics/test_readme_joint_example.cpp",
      root + "/tests/physics/test_unique_world.cpp",
      root + "/tests/replay/test_readme_example.cpp",
      root + "/tests/replay/test_session_readme.cpp",
  };
  const std::vector<std::string> readme = split_lines(tandem::readme::text());
  REQUIRE(!readme.empty());
  size_t checked = 0;
  for (const std::string& path : sources) {
    for (const Block& block : marked_blocks(path)) {
      INFO(path << ": the " << block.name << " (" << block.lines.size() << " lines) differs from README.md");
      CHECK(readme_contains(readme, block.lines));
      ++checked;
    }
  }
  CHECK(checked >= 6);  // physics, events, joint, owning, replay, session
}
