// scene_read.cpp — the scene reader's error path and field readers
// (scene_read.h).
#include "scene_read.h"

#include <algorithm>

#include "fixed/fixed_math.h"

namespace tandem::scene::detail {

std::string show_path(const std::string& path) { return path.empty() ? "/" : path; }

[[noreturn]] void fail(const std::string& path, const std::string& message) {
  throw SceneError{show_path(path) + ": " + message};
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " or " : ", ";
    out += "\"" + names[i] + "\"";
  }
  return out;
}

// Levenshtein distance, for "did you mean".
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::string did_you_mean(const std::string& word, const std::vector<std::string>& known) {
  size_t best = SIZE_MAX;
  std::string best_word;
  for (const std::string& k : known) {
    const size_t d = edit_distance(word, k);
    if (d < best) best = d, best_word = k;
  }
  if (best_word.empty() || best > std::max<size_t>(2, word.size() / 3)) return "";
  return " (did you mean \"" + best_word + "\"?)";
}

std::string got(const JsonValue& v) {
  switch (v.kind) {
    case JsonValue::Kind::integer:
    case JsonValue::Kind::number: return std::string("got ") + v.text;
    case JsonValue::Kind::string: return "got a string";
    default: return std::string("got ") + json_kind_name(v.kind);
  }
}

// --- scalar readers ---------------------------------------------------------
Q32 read_q32(const JsonValue& v, const std::string& path) {
  if (v.kind != JsonValue::Kind::number && v.kind != JsonValue::Kind::integer)
    fail(path, "expected a number, " + got(v));
  const auto p = parse_q32(v.text);
  if (!p.ok()) {
    if (std::string(p.error) == "out of range")
      fail(path, "expected a number within ±2147483648 (Q32.32), got " + v.text);
    fail(path, "expected a number: " + describe_parse_error(v.text, p.error, p.error_offset));
  }
  return p.value;
}

Q32 read_q32_min(const JsonValue& v, const std::string& path, Q32 lo, bool exclusive) {
  const Q32 q = read_q32(v, path);
  if (exclusive ? q <= lo : q < lo)
    fail(path, std::string("expected a number ") + (exclusive ? "> " : "≥ ") + to_string(lo) + ", got " + v.text);
  return q;
}

int64_t read_int(const JsonValue& v, const std::string& path, int64_t lo, int64_t hi) {
  const std::string range = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (v.kind == JsonValue::Kind::number) fail(path, "expected " + range + " (no fraction or exponent), " + got(v));
  if (v.kind != JsonValue::Kind::integer) fail(path, "expected " + range + ", " + got(v));
  const bool negative = !v.text.empty() && v.text[0] == '-';
  uint64_t magnitude = 0;
  for (size_t i = negative ? 1 : 0; i < v.text.size(); ++i) {
    if (magnitude > (UINT64_MAX - 9) / 10) fail(path, "expected " + range + ", " + got(v));
    magnitude = magnitude * 10 + static_cast<uint64_t>(v.text[i] - '0');
  }
  if (magnitude > (uint64_t{1} << 62)) fail(path, "expected " + range + ", " + got(v));
  const int64_t value = negative ? -static_cast<int64_t>(magnitude) : static_cast<int64_t>(magnitude);
  if (value < lo || value > hi) fail(path, "expected " + range + ", " + got(v));
  return value;
}

uint64_t read_u64(const JsonValue& v, const std::string& path) {
  const char* expected = "expected an unsigned 64-bit integer or a \"0x...\" hex string, ";
  if (v.kind == JsonValue::Kind::string) {
    const std::string& s = v.text;
    if (s.size() < 3 || s.size() > 18 || s[0] != '0' || (s[1] != 'x' && s[1] != 'X'))
      fail(path, std::string(expected) + "got \"" + s + "\"");
    uint64_t out = 0;
    for (size_t i = 2; i < s.size(); ++i) {
      const char c = s[i];
      int digit = -1;
      if (c >= '0' && c <= '9') digit = c - '0';
      else if (c >= 'a' && c <= 'f') digit = c - 'a' + 10;
      else if (c >= 'A' && c <= 'F') digit = c - 'A' + 10;
      if (digit < 0) fail(path, std::string(expected) + "got \"" + s + "\"");
      out = (out << 4) | static_cast<uint64_t>(digit);
    }
    return out;
  }
  if (v.kind != JsonValue::Kind::integer || (!v.text.empty() && v.text[0] == '-'))
    fail(path, std::string(expected) + got(v));
  uint64_t out = 0;
  for (char c : v.text) {
    const auto digit = static_cast<uint64_t>(c - '0');
    if (out > (UINT64_MAX - digit) / 10) fail(path, std::string(expected) + got(v));
    out = out * 10 + digit;
  }
  return out;
}

bool read_bool(const JsonValue& v, const std::string& path) {
  if (v.kind != JsonValue::Kind::boolean) fail(path, "expected true or false, " + got(v));
  return v.boolean;
}

std::string read_string(const JsonValue& v, const std::string& path) {
  if (v.kind != JsonValue::Kind::string) fail(path, "expected a string, " + got(v));
  return v.text;
}

std::string read_enum(const JsonValue& v, const std::string& path, const std::vector<std::string>& names) {
  if (v.kind != JsonValue::Kind::string) fail(path, "expected one of " + quoted_list(names) + ", " + got(v));
  if (std::find(names.begin(), names.end(), v.text) == names.end())
    fail(path, "unknown value \"" + v.text + "\"" + did_you_mean(v.text, names) + "; expected one of " +
                   quoted_list(names));
  return v.text;
}

Vec2 read_vec2(const JsonValue& v, const std::string& path) {
  if (v.kind != JsonValue::Kind::array || v.items.size() != 2)
    fail(path, "expected [x, y] (an array of two numbers), " +
                   (v.kind == JsonValue::Kind::array ? "got " + std::to_string(v.items.size()) + " elements" : got(v)));
  return Vec2{read_q32(v.items[0], path + "/0"), read_q32(v.items[1], path + "/1")};
}

std::vector<Vec2> read_points(const JsonValue& v, const std::string& path, size_t min_count, size_t max_count) {
  if (v.kind != JsonValue::Kind::array) fail(path, "expected an array of [x, y] points, " + got(v));
  if (v.items.size() < min_count || v.items.size() > max_count)
    fail(path, "expected " + std::to_string(min_count) + " to " + std::to_string(max_count) + " points, got " +
                   std::to_string(v.items.size()));
  std::vector<Vec2> out;
  for (size_t i = 0; i < v.items.size(); ++i) out.push_back(read_vec2(v.items[i], path + "/" + std::to_string(i)));
  return out;
}

const std::vector<JsonValue>& read_array(const JsonValue& v, const std::string& path) {
  if (v.kind != JsonValue::Kind::array) fail(path, "expected an array, " + got(v));
  return v.items;
}

AABB read_box(const JsonValue& v, const std::string& path) {
  Obj o(v, path, {&k_view_keys});
  AABB box{read_vec2(o.need("lower"), o.at("lower")), read_vec2(o.need("upper"), o.at("upper"))};
  if (!(box.lower.x < box.upper.x && box.lower.y < box.upper.y))
    fail(path, "expected lower < upper in both x and y");
  return box;
}

}  // namespace tandem::scene::detail
