// str_cat.h — text pieces joined by appending, for error messages.
#pragma once

#include <string>

namespace tandem {

/// Joins text pieces (anything std::string::append takes in one argument:
/// std::string, std::string_view, const char*) into one string by appending.
/// Messages use it instead of `"literal" + std::string` chains, on which
/// g++ 12 at -O3 reports a false -Wrestrict (it once broke the i686 build).
template <typename... Parts>
std::string str_cat(const Parts&... parts) {
  std::string s;
  (s.append(parts), ...);
  return s;
}

}  // namespace tandem
