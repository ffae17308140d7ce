// json_tree.cpp — builds a JsonValue tree with nlohmann's SAX parser (the only
// translation unit that includes nlohmann/json.hpp). See json_tree.h.
#include "json_tree.h"

#include <nlohmann/json.hpp>

namespace tandem::scene {

const char* json_kind_name(JsonValue::Kind kind) {
  switch (kind) {
    case JsonValue::Kind::null_value: return "null";
    case JsonValue::Kind::boolean: return "a boolean";
    case JsonValue::Kind::integer: return "an integer";
    case JsonValue::Kind::number: return "a number";
    case JsonValue::Kind::string: return "a string";
    case JsonValue::Kind::array: return "an array";
    case JsonValue::Kind::object: return "an object";
  }
  return "?";
}

namespace {

// Escapes a key for a JSON pointer (RFC 6901).
std::string pointer_token(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

class TreeBuilder {
 public:
  using json = nlohmann::json;
  using number_integer_t = json::number_integer_t;
  using number_unsigned_t = json::number_unsigned_t;
  using number_float_t = json::number_float_t;
  using string_t = json::string_t;
  using binary_t = json::binary_t;

  JsonValue root;
  std::string error;

  bool null() { return add(JsonValue{}); }
  bool boolean(bool b) {
    JsonValue v;
    v.kind = JsonValue::Kind::boolean;
    v.boolean = b;
    return add(std::move(v));
  }
  bool number_integer(number_integer_t i) { return add_number(JsonValue::Kind::integer, std::to_string(i)); }
  bool number_unsigned(number_unsigned_t u) { return add_number(JsonValue::Kind::integer, std::to_string(u)); }
  // The binary floating-point value is ignored: only the text is kept.
  bool number_float(number_float_t, const string_t& text) {
    // Integers too large for 64 bits arrive here with integer text.
    const bool integral = text.find_first_of(".eE") == std::string::npos;
    return add_number(integral ? JsonValue::Kind::integer : JsonValue::Kind::number, text);
  }
  bool string(string_t& s) {
    JsonValue v;
    v.kind = JsonValue::Kind::string;
    v.text = std::move(s);
    return add(std::move(v));
  }
  bool binary(binary_t&) { return fail("binary values are not JSON"); }
  bool start_object(std::size_t) {
    JsonValue v;
    v.kind = JsonValue::Kind::object;
    return open(std::move(v));
  }
  bool key(string_t& k) {
    JsonValue* top = stack_.back();
    for (const std::string& existing : top->keys)
      if (existing == k) return fail("duplicate key \"" + k + "\" at " + path_of_top() + "/" + pointer_token(k));
    pending_key_ = std::move(k);
    return true;
  }
  bool end_object() {
    stack_.pop_back();
    path_.pop_back();
    return true;
  }
  bool start_array(std::size_t) {
    JsonValue v;
    v.kind = JsonValue::Kind::array;
    return open(std::move(v));
  }
  bool end_array() { return end_object(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& ex) {
    // ex.what() reads "[json.exception.parse_error.101] parse error at line 3, column 7: ..."
    std::string what = ex.what();
    const size_t cut = what.find("] ");
    error = cut == std::string::npos ? what : what.substr(cut + 2);
    return false;
  }

 private:
  std::vector<JsonValue*> stack_;
  std::vector<std::string> path_;  // one token per open container: how it was reached
  std::string pending_key_;
  bool have_root_ = false;

  std::string path_of_top() const {
    std::string p;
    for (size_t i = 1; i < path_.size(); ++i) p += "/" + path_[i];
    return p.empty() ? "(the top level)" : p;
  }
  bool fail(std::string message) {
    if (error.empty()) error = std::move(message);
    return false;
  }
  bool add_number(JsonValue::Kind kind, std::string text) {
    JsonValue v;
    v.kind = kind;
    v.text = std::move(text);
    return add(std::move(v));
  }
  // Places v in the open container (or as the root); returns its address.
  JsonValue* place(JsonValue v, std::string* token) {
    if (stack_.empty()) {
      root = std::move(v);
      have_root_ = true;
      *token = "";
      return &root;
    }
    JsonValue* top = stack_.back();
    if (top->kind == JsonValue::Kind::object) {
      *token = pointer_token(pending_key_);
      top->keys.push_back(std::move(pending_key_));
    } else {
      *token = std::to_string(top->items.size());
    }
    top->items.push_back(std::move(v));
    return &top->items.back();
  }
  bool add(JsonValue v) {
    std::string token;
    place(std::move(v), &token);
    return true;
  }
  bool open(JsonValue v) {
    if (static_cast<int>(stack_.size()) >= k_max_json_depth)
      return fail("nesting deeper than " + std::to_string(k_max_json_depth) + " levels at " + path_of_top());
    std::string token;
    JsonValue* placed = place(std::move(v), &token);
    stack_.push_back(placed);  // the parent's vector does not grow until this closes
    path_.push_back(token);
    return true;
  }
};

}  // namespace

JsonParse parse_json_tree(std::string_view text) {
  TreeBuilder builder;
  JsonParse out;
  const bool ok = nlohmann::json::sax_parse(text.begin(), text.end(), &builder, nlohmann::json::input_format_t::json,
                                            /*strict=*/true, /*ignore_comments=*/false);
  if (!ok || !builder.error.empty()) {
    out.error = builder.error.empty() ? "malformed JSON" : builder.error;
    return out;
  }
  out.value = std::move(builder.root);
  return out;
}

}  // namespace tandem::scene
