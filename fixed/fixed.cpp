// fixed.cpp — out-of-line parts of fixed.h: exact decimal output and parse
// error text.
#include "fixed/fixed.h"

#include <cstdlib>

namespace tandem {

std::string describe_parse_error(std::string_view text, const char* error, size_t offset) {
  std::string s = error ? error : "no error";
  if (offset < text.size()) {
    s += " '";
    s += text[offset];
    s += "'";
  }
  s += " at offset " + std::to_string(offset) + " in \"";
  s.append(text.data(), text.size());
  s += "\"";
  return s;
}

template <typename R, int F>
std::string to_string(Fixed<R, F> a) {
  const uint64_t mag = detail::magnitude(a.raw);
  std::string s = a.raw < 0 ? "-" : "";
  s += std::to_string(mag >> F);
  uint64_t frac = mag & ((uint64_t{1} << F) - 1);
  if (frac != 0) {
    s += '.';
    // Each step multiplies the fraction by 10; frac < 2^32, so frac·10 < 2^36.
    while (frac != 0) {
      frac *= 10;
      s += static_cast<char>('0' + (frac >> F));
      frac &= (uint64_t{1} << F) - 1;
    }
  }
  return s;
}

template std::string to_string(Q32);
template std::string to_string(Q16);

namespace detail {
void literal_error(const char* message) {
  // Only reachable at run time if a literal were evaluated outside constant
  // evaluation, which consteval forbids.
  (void)message;
  std::abort();
}
}  // namespace detail

}  // namespace tandem
