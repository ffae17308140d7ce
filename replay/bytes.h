// bytes.h — explicit little-endian byte writing and bounds-checked reading,
// the only way replay/ turns values into bytes and back.
//
// DESIGN. Every multi-byte value is written and read one byte at a time with
// shifts on unsigned types (least significant byte first), so the encoding
// never depends on the host's endianness, struct layout or padding; compilers
// fold the byte loops into single loads and stores on little-endian hosts.
// Signed values travel as their two's-complement bit pattern, converted
// through the unsigned type (well defined in C++20 both ways). Q32 / Q16 are
// their raw integers; Vec2 is x then y; Rot is c then s.
//
// ByteWriter has two modes: appending to a std::vector<uint8_t>, or writing
// into a caller buffer of fixed capacity. In buffer mode nothing is ever
// written at or beyond the capacity; the writer keeps counting, so size()
// is the size the full encoding needs and overflowed() tells the caller to
// retry with a buffer of that size.
//
// ByteReader reads over a span and never past its end. Every read names what
// it expects; the first read that does not fit records a message
//   "offset 1234: expected 8 bytes of body 17 linear_velocity.x, 3 left"
// (the offset is where that read started; "body 17" is the context set by
// set_context) and makes every later read fail (returning zero), so a decoder
// can read a whole record and check ok() once. Decoders also call fail() for
// values that fit but are invalid ("expected body type 0..2, got 7"). A count
// read from data is checked against the bytes that remain (count ×
// minimum bytes per item) before anything is allocated for it: read_count().
//
// Rejected: memcpy of host integers plus byte swaps on big-endian hosts
// (needs an endianness detection that the cross builds would have to get
// right; the shift form is portable by construction and as fast once folded).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "fixed/fixed.h"
#include "fixed/vec2.h"

namespace tandem {

/// Appends or writes explicit little-endian values (see the file comment).
class ByteWriter {
 public:
  /// Appends to *out (which keeps its existing contents). `out` must outlive
  /// the writer.
  explicit ByteWriter(std::vector<uint8_t>* out) : vector_(out) {}
  /// Writes into buffer[0, capacity); bytes past the capacity are counted but
  /// not written (see overflowed()). `buffer` may be null when capacity is 0
  /// (a size-only pass).
  ByteWriter(uint8_t* buffer, size_t capacity) : buffer_(buffer), capacity_(capacity) {}

  /// One byte.
  void u8(uint8_t v) {
    uint8_t b[1] = {v};
    put(b, 1);
  }
  /// A bool as one byte, 0 or 1.
  void boolean(bool v) { u8(v ? 1 : 0); }
  /// Two bytes, little-endian.
  void u16(uint16_t v) {
    uint8_t b[2] = {static_cast<uint8_t>(v), static_cast<uint8_t>(v >> 8)};
    put(b, 2);
  }
  /// Four bytes, little-endian.
  void u32(uint32_t v) {
    uint8_t b[4];
    for (int i = 0; i < 4; ++i) b[i] = static_cast<uint8_t>(v >> (8 * i));
    put(b, 4);
  }
  /// Eight bytes, little-endian.
  void u64(uint64_t v) {
    uint8_t b[8];
    for (int i = 0; i < 8; ++i) b[i] = static_cast<uint8_t>(v >> (8 * i));
    put(b, 8);
  }
  /// A signed 32-bit value as its two's-complement bits.
  void i32(int32_t v) { u32(static_cast<uint32_t>(v)); }
  /// A signed 64-bit value as its two's-complement bits.
  void i64(int64_t v) { u64(static_cast<uint64_t>(v)); }
  /// A Q32.32 as its raw int64.
  void q32(Q32 v) { i64(v.raw); }
  /// A Q16.16 as its raw int32.
  void q16(Q16 v) { i32(v.raw); }
  /// x then y.
  void vec2(Vec2 v) {
    q32(v.x);
    q32(v.y);
  }
  /// c then s.
  void rot(Rot v) {
    q32(v.c);
    q32(v.s);
  }
  /// Raw bytes, as they are.
  void bytes(const uint8_t* data, size_t size) {
    if (size != 0) put(data, size);
  }

  /// Bytes written so far (buffer mode: also those that did not fit); in
  /// vector mode, bytes appended by this writer.
  size_t size() const { return size_; }
  /// Buffer mode: true when some byte did not fit in the capacity.
  bool overflowed() const { return vector_ == nullptr && size_ > capacity_; }

 private:
  void put(const uint8_t* data, size_t n) {
    if (vector_ != nullptr) {
      // resize + memcpy rather than insert(): g++ 12 at -O3 reports a false
      // -Wstringop-overflow for vector<uint8_t>::insert of a few bytes.
      const size_t at = vector_->size();
      vector_->resize(at + n);
      std::memcpy(vector_->data() + at, data, n);
    } else if (size_ <= capacity_ && n <= capacity_ - size_) {
      std::memcpy(buffer_ + size_, data, n);
    }
    size_ += n;
  }

  std::vector<uint8_t>* vector_ = nullptr;
  uint8_t* buffer_ = nullptr;
  size_t capacity_ = 0;
  size_t size_ = 0;
};

/// Bounds-checked little-endian reads over a span (see the file comment).
class ByteReader {
 public:
  /// Reads data[0, size). The data must outlive the reader.
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  /// Reads a span.
  explicit ByteReader(std::span<const uint8_t> data) : data_(data.data()), size_(data.size()) {}

  /// Names the record being read in failure messages ("body", 17 → "body
  /// 17 <what>"); index < 0 gives just the kind; a null kind clears it. The
  /// string must outlive the reads (use literals).
  void set_context(const char* kind, int64_t index = -1) {
    context_kind_ = kind;
    context_index_ = index;
  }

  /// One byte; `what` names it in the failure message.
  uint8_t u8(const char* what) {
    const uint8_t* p = take(1, what);
    return p == nullptr ? 0 : p[0];
  }
  /// One byte that must be 0 or 1 (anything else fails).
  bool boolean(const char* what) {
    const size_t at = offset_;
    const uint8_t v = u8(what);
    if (v > 1) fail_at(at, std::string("expected ") + describe_what(what) + " 0 or 1, got " + std::to_string(v));
    return v == 1;
  }
  /// Two bytes, little-endian.
  uint16_t u16(const char* what) {
    const uint8_t* p = take(2, what);
    if (p == nullptr) return 0;
    return static_cast<uint16_t>(p[0] | (p[1] << 8));
  }
  /// Four bytes, little-endian.
  uint32_t u32(const char* what) {
    const uint8_t* p = take(4, what);
    if (p == nullptr) return 0;
    uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<uint32_t>(p[i]);
    return v;
  }
  /// Eight bytes, little-endian.
  uint64_t u64(const char* what) {
    const uint8_t* p = take(8, what);
    if (p == nullptr) return 0;
    uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = (v << 8) | static_cast<uint32_t>(p[i]);
    return v;
  }
  /// A signed 32-bit value from its two's-complement bits.
  int32_t i32(const char* what) { return static_cast<int32_t>(u32(what)); }
  /// A signed 64-bit value from its two's-complement bits.
  int64_t i64(const char* what) { return static_cast<int64_t>(u64(what)); }
  /// A Q32.32 from its raw int64 (any raw value, including the type's
  /// minimum; callers that need the symmetric range check it).
  Q32 q32(const char* what) { return Q32::from_raw(i64(what)); }
  /// A Q16.16 from its raw int32.
  Q16 q16(const char* what) { return Q16::from_raw(i32(what)); }
  /// x then y; `what_x` / `what_y` name them ("linear_velocity.x").
  Vec2 vec2(const char* what_x, const char* what_y) {
    Vec2 v;
    v.x = q32(what_x);
    v.y = q32(what_y);
    return v;
  }
  /// c then s.
  Rot rot(const char* what_c, const char* what_s) {
    Rot r;
    r.c = q32(what_c);
    r.s = q32(what_s);
    return r;
  }
  /// `n` raw bytes as a span into the data (empty on failure).
  std::span<const uint8_t> bytes(size_t n, const char* what) {
    const uint8_t* p = take(n, what);
    if (p == nullptr) return {};
    return {p, n};
  }

  /// Reads a u32 count of items that each take at least `min_item_bytes`
  /// bytes, and fails (returning 0) when count > max_count or when the bytes
  /// left cannot hold that many items — so a count from corrupt data never
  /// sizes an allocation beyond the input.
  uint32_t read_count(const char* what, size_t min_item_bytes, uint32_t max_count = UINT32_MAX) {
    const size_t at = offset_;
    const uint32_t n = u32(what);
    if (!ok()) return 0;
    if (n > max_count) {
      fail_at(at, std::string("expected ") + describe_what(what) + " at most " + std::to_string(max_count) +
                      ", got " + std::to_string(n));
      return 0;
    }
    if (min_item_bytes != 0 && n > remaining() / min_item_bytes) {
      fail_at(at, std::string("expected ") + describe_what(what) + " of at most " +
                      std::to_string(remaining() / min_item_bytes) + " (" + std::to_string(remaining()) +
                      " bytes left, at least " + std::to_string(min_item_bytes) + " per item), got " +
                      std::to_string(n));
      return 0;
    }
    return n;
  }

  /// Records a failure at the current offset (no-op if one is recorded):
  /// the message becomes "offset N: " + message.
  void fail(const std::string& message) { fail_at(offset_, message); }
  /// Records a failure at `offset` (the first failure wins).
  void fail_at(size_t offset, const std::string& message) {
    if (failed_) return;
    failed_ = true;
    error_offset_ = offset;
    error_.assign("offset ");
    error_.append(std::to_string(offset));
    error_.append(": ");
    error_.append(message);
  }
  /// "body 17 what" / "what" with the current context, for messages.
  std::string describe_what(const char* what) const {
    // Built by appending: gcc 12 at -O3 misreports `"literal" + std::string`
    // (-Wrestrict false positive).
    std::string s;
    if (context_kind_ != nullptr) {
      s.append(context_kind_);
      if (context_index_ >= 0) {
        s.push_back(' ');
        s.append(std::to_string(context_index_));
      }
      s.push_back(' ');
    }
    s.append(what);
    return s;
  }

  /// True while no read has failed.
  bool ok() const { return !failed_; }
  /// The failure message ("offset N: expected ..."), empty while ok.
  const std::string& error() const { return error_; }
  /// Where the first failure happened (0 while ok).
  size_t error_offset() const { return error_offset_; }
  /// The next byte's offset from the start.
  size_t offset() const { return offset_; }
  /// Bytes not read yet (0 after a failure).
  size_t remaining() const { return failed_ ? 0 : size_ - offset_; }
  /// True when every byte has been read without failure.
  bool at_end() const { return !failed_ && offset_ == size_; }

 private:
  const uint8_t* take(size_t n, const char* what) {
    if (failed_ || n > size_ - offset_) [[unlikely]] {
      fail_take(n, what);
      return nullptr;
    }
    const uint8_t* p = data_ + offset_;
    offset_ += n;
    return p;
  }
  /// take()'s failure path, out of line so that take() inlines into every
  /// read (the message is built only here).
  [[gnu::cold, gnu::noinline]] void fail_take(size_t n, const char* what) {
    if (failed_) return;
    {
      std::string m("expected ");
      m.append(std::to_string(n));
      m.append(n == 1 ? " byte of " : " bytes of ");
      m.append(describe_what(what));
      m.append(", ");
      m.append(std::to_string(size_ - offset_));
      m.append(" left");
      fail_at(offset_, m);
    }
  }

  const uint8_t* data_ = nullptr;
  size_t size_ = 0;
  size_t offset_ = 0;
  bool failed_ = false;
  size_t error_offset_ = 0;
  std::string error_;
  const char* context_kind_ = nullptr;
  int64_t context_index_ = -1;
};

}  // namespace tandem
