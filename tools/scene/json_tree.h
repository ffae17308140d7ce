// json_tree.h — a small JSON document tree that keeps every number as its
// original decimal text (tools only).
//
// Why not nlohmann::json's own tree: it stores numbers as binary floating
// point, and a scene's "0.1" must become parse_q32("0.1") — the same bits on
// every machine — never the nearest binary fraction of a double. The tree is
// built through nlohmann's SAX interface, which hands over the text of every
// number; nlohmann is included by json_tree.cpp only, so the (heavy) header is
// compiled once.
//
// Object members keep their file order; a duplicate key is an error. Nesting
// deeper than k_max_json_depth is refused (the readers recurse).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tandem::scene {

/// Deepest nesting of arrays and objects accepted.
inline constexpr int k_max_json_depth = 64;

/// One JSON value.
struct JsonValue {
  enum class Kind { null_value, boolean, integer, number, string, array, object };
  Kind kind = Kind::null_value;
  bool boolean = false;
  /// number / integer: the original text ("0.1", "-3", "1e-2"); string: the
  /// decoded UTF-8 text.
  std::string text;
  std::vector<std::string> keys;  ///< object: member names, file order
  std::vector<JsonValue> items;   ///< array: elements; object: member values (parallel to keys)
};

/// "null", "a boolean", "an integer", "a number", "a string", "an array", "an object".
const char* json_kind_name(JsonValue::Kind kind);

/// The outcome of parse_json_tree: the tree, or an error message.
struct JsonParse {
  JsonValue value;
  std::string error;  ///< empty on success; names line and column of a syntax error
  bool ok() const { return error.empty(); }
};

/// Parses JSON text (RFC 8259) into a tree. Errors: syntax (with line and
/// column), duplicate keys (with the JSON path), nesting too deep.
JsonParse parse_json_tree(std::string_view text);

}  // namespace tandem::scene
