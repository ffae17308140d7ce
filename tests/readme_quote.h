// readme_quote.h — tests that assert the figures README.md quotes.
//
// A test that computes a figure the README quotes formats it at the quoted
// precision and checks that README.md (path: the TANDEM_README_PATH compile
// definition) still contains that exact text. A change that moves a figure
// therefore fails the test until the README is updated, and a README edit
// that changes a figure fails it until the test agrees. Figures only a
// benchmark can produce (timings) are not asserted; the README labels them
// as benchmark measurements with machine and date.
#pragma once

#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace tandem::readme {

/// README.md's text (read once).
inline const std::string& text() {
  static const std::string content = [] {
    std::ifstream in(TANDEM_README_PATH, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }();
  return content;
}

/// v with exactly `decimals` decimals, rounded to nearest ("1.0007").
inline std::string fixed(long double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*Lf", decimals, v);
  return buf;
}

/// Checks that README.md contains `quote` verbatim.
inline void check_quotes(const std::string& quote) {
  INFO("README.md (" << TANDEM_README_PATH << ") should contain: \"" << quote << "\"");
  REQUIRE(!text().empty());
  CHECK(text().find(quote) != std::string::npos);
}

}  // namespace tandem::readme
