// state_diff.cpp — deltas of state images against a base image and
// field-level diffs of decoded states (state.h describes both).
#include "replay/state_internal.h"

#define XXH_INLINE_ALL
#include <xxhash.h>

namespace tandem {

// ---------------------------------------------------------------------------
// Deltas
// ---------------------------------------------------------------------------

namespace {

constexpr uint8_t k_delta_magic[4] = {'T', 'N', 'D', 'D'};
constexpr uint32_t k_delta_version = 1;

void put_varint(std::vector<uint8_t>* out, uint64_t v) {
  while (v >= 0x80) {
    out->push_back(static_cast<uint8_t>(v | 0x80));
    v >>= 7;
  }
  out->push_back(static_cast<uint8_t>(v));
}

/// LEB128, at most 10 bytes; fails (false) on truncation or overlong input.
bool get_varint(ByteReader* r, const char* what, uint64_t* out) {
  uint64_t v = 0;
  for (int shift = 0; shift < 64; shift += 7) {
    const size_t at = r->offset();
    const uint8_t b = r->u8(what);
    if (!r->ok()) return false;
    if (shift == 63 && b > 1) {
      r->fail_at(at, std::string("expected ") + what + " (a varint below 2^64)");
      return false;
    }
    v |= static_cast<uint64_t>(b & 0x7F) << shift;
    if ((b & 0x80) == 0) {
      *out = v;
      return true;
    }
  }
  r->fail(std::string("expected the end of varint ") + what);
  return false;
}

uint8_t base_byte(const uint8_t* base, size_t base_size, size_t i) { return i < base_size ? base[i] : 0; }

}  // namespace

void encode_state_delta(const uint8_t* base, size_t base_size, const uint8_t* image, size_t image_size,
                        std::vector<uint8_t>* out) {
  out->clear();
  ByteWriter header(out);
  header.bytes(k_delta_magic, 4);
  header.u32(k_delta_version);
  header.u64(image_size);
  header.u64(XXH3_64bits(base, base_size));
  const size_t common = std::min(base_size, image_size);
  size_t i = 0;
  while (i < image_size) {
    // A run of bytes equal to the base (only within the base).
    size_t run = 0;
    while (i + run + 8 <= common && std::memcmp(base + i + run, image + i + run, 8) == 0) run += 8;
    while (i + run < common && base[i + run] == image[i + run]) ++run;
    put_varint(out, run);
    i += run;
    if (i >= image_size) break;
    // Literal bytes until 4 equal bytes in a row (or the end).
    size_t end = i;
    size_t same = 0;
    while (end < image_size) {
      if (end < common && base[end] == image[end]) {
        if (++same == 4) {
          end -= 3;
          break;
        }
      } else {
        same = 0;
      }
      ++end;
    }
    if (end >= image_size) end = image_size;
    put_varint(out, end - i);
    for (size_t k = i; k < end; ++k) out->push_back(static_cast<uint8_t>(image[k] ^ base_byte(base, base_size, k)));
    i = end;
  }
}

Status apply_state_delta(const uint8_t* base, size_t base_size, const uint8_t* delta, size_t delta_size,
                         std::vector<uint8_t>* out_image) {
  const auto bad = [](const std::string& msg) {
    return Status{StatusCode::invalid_argument, "apply_state_delta: " + msg};
  };
  if (delta == nullptr && delta_size != 0) return bad("null delta with size " + std::to_string(delta_size));
  ByteReader r(delta, delta_size);
  const std::span<const uint8_t> magic = r.bytes(4, "magic \"TNDD\"");
  if (!r.ok()) return bad(r.error());
  if (std::memcmp(magic.data(), k_delta_magic, 4) != 0) return bad("offset 0: expected magic \"TNDD\" (a state delta)");
  const uint32_t version = r.u32("delta version");
  if (r.ok() && version != k_delta_version) {
    return bad("offset 4: expected delta version " + std::to_string(k_delta_version) + ", got " +
               std::to_string(version));
  }
  const uint64_t image_size = r.u64("image size");
  const uint64_t base_hash = r.u64("base hash");
  if (!r.ok()) return bad(r.error());
  if (base_hash != XXH3_64bits(base, base_size)) {
    return bad("offset 16: the delta was made against another base (base hash differs)");
  }
  if (image_size > static_cast<uint64_t>(base_size) + delta_size) {
    return bad("offset 8: expected an image size of at most " + std::to_string(base_size + delta_size) +
               " (base + delta), got " + std::to_string(image_size));
  }
  const size_t n = static_cast<size_t>(image_size);
  out_image->resize(n);
  uint8_t* img = out_image->data();
  size_t i = 0;
  while (i < n) {
    uint64_t run = 0;
    const size_t run_at = r.offset();
    if (!get_varint(&r, "unchanged run", &run)) return bad(r.error());
    if (run > n - i || run > (i < base_size ? base_size - i : 0)) {
      return bad("offset " + std::to_string(run_at) + ": expected an unchanged run within the base and the image (" +
                 std::to_string(std::min(n - i, i < base_size ? base_size - i : 0)) + " bytes), got " +
                 std::to_string(run));
    }
    if (run != 0) std::memcpy(img + i, base + i, static_cast<size_t>(run));
    i += static_cast<size_t>(run);
    if (i >= n) break;
    uint64_t lit = 0;
    const size_t lit_at = r.offset();
    if (!get_varint(&r, "changed run", &lit)) return bad(r.error());
    if (lit == 0 || lit > n - i || lit > r.remaining()) {
      return bad("offset " + std::to_string(lit_at) + ": expected a changed run of 1.." +
                 std::to_string(std::min(n - i, r.remaining())) + " bytes, got " + std::to_string(lit));
    }
    const std::span<const uint8_t> bytes = r.bytes(static_cast<size_t>(lit), "changed bytes");
    for (size_t k = 0; k < bytes.size(); ++k, ++i) img[i] = static_cast<uint8_t>(bytes[k] ^ base_byte(base, base_size, i));
  }
  if (!r.at_end()) {
    return bad("offset " + std::to_string(r.offset()) + ": expected the end of the delta, " +
               std::to_string(r.remaining()) + " bytes left over");
  }
  return Status{};
}

std::string q32_raw_text(int64_t raw) {
  if (raw == INT64_MIN) return "-2147483648";
  return to_string(Q32::from_raw(raw));
}

std::string StateDifference::describe() const {
  if (!differs) return "identical";
  std::string who = kind + " " + std::to_string(index);
  if (index2 >= 0) who = kind + " (" + std::to_string(index) + ", " + std::to_string(index2) + ")";
  // The generation is noise while both sides agree (the index names the
  // record); it is printed only when the two sides' slots were reused a
  // different number of times, and not again for the "generation" field.
  if (!missing_in_a && !missing_in_b && generation != generation_b && field != "generation") {
    who += " (generation " + std::to_string(generation) + " in a, " + std::to_string(generation_b) + " in b)";
  }
  if (missing_in_a) return who + ": only in b";
  if (missing_in_b) return who + ": only in a";
  const auto text = [&](int64_t v) {
    return is_q32 ? q32_raw_text(v) + " (raw " + std::to_string(v) + ")" : std::to_string(v);
  };
  return who + " " + field + ": a = " + text(value_a) + ", b = " + text(value_b);
}

namespace {
/// The position of a record kind's section in canonical order.
int32_t kind_rank(const std::string& kind) {
  static const char* const kinds[] = {"world",   "body_slot", "body",           "shape_slot", "shape",
                                      "contact", "touching",  "sensor_overlap", "joint_slot", "joint",
                                      "joint_event"};
  for (int32_t i = 0; i < 11; ++i) {
    if (kind == kinds[i]) return i;
  }
  return 11;
}
/// Marks `d` as differing at record `r` (its generation read on side a) whose
/// slot generation on side b is `generation_b`.
void mark_record(StateDifference* d, const DecodedRecord& r, uint32_t generation_b) {
  d->differs = true;
  d->kind = r.kind;
  d->index = r.index;
  d->index2 = r.index2;
  d->generation = r.generation;
  d->generation_b = generation_b;
}
}  // namespace

StateDifference diff_world_states(const DecodedState& a, const DecodedState& b) {
  StateDifference d;
  const size_t n = std::min(a.records.size(), b.records.size());
  for (size_t i = 0; i < n; ++i) {
    const DecodedRecord& ra = a.records[i];
    const DecodedRecord& rb = b.records[i];
    if (ra.kind != rb.kind || ra.index != rb.index || ra.index2 != rb.index2) {
      // The record that sorts first in canonical order is the one the other
      // side lacks; kinds differ only at a section boundary, where the
      // shorter section is missing a record.
      const int32_t rank_a = kind_rank(ra.kind);
      const int32_t rank_b = kind_rank(rb.kind);
      const bool a_first = rank_a != rank_b ? rank_a < rank_b
                                            : (ra.index < rb.index || (ra.index == rb.index && ra.index2 < rb.index2));
      const DecodedRecord& r = a_first ? ra : rb;
      mark_record(&d, r, r.generation);
      d.missing_in_b = a_first;
      d.missing_in_a = !a_first;
      return d;
    }
    const size_t fields = std::min(ra.fields.size(), rb.fields.size());
    for (size_t f = 0; f < fields; ++f) {
      const DecodedField& fa = ra.fields[f];
      const DecodedField& fb = rb.fields[f];
      if (fa.name != fb.name || fa.value != fb.value) {
        mark_record(&d, ra, rb.generation);
        d.field = fa.name == fb.name ? fa.name : fa.name + " / " + fb.name;
        d.value_a = fa.value;
        d.value_b = fb.value;
        d.is_q32 = fa.is_q32;
        return d;
      }
    }
    if (ra.fields.size() != rb.fields.size()) {
      mark_record(&d, ra, rb.generation);
      const bool a_longer = ra.fields.size() > rb.fields.size();
      d.field = (a_longer ? ra.fields[fields] : rb.fields[fields]).name + " (present on one side only)";
      d.value_a = static_cast<int64_t>(ra.fields.size());
      d.value_b = static_cast<int64_t>(rb.fields.size());
      return d;
    }
    if (ra.generation != rb.generation) {
      mark_record(&d, ra, rb.generation);
      d.field = "generation";
      d.value_a = ra.generation;
      d.value_b = rb.generation;
      return d;
    }
  }
  if (a.records.size() != b.records.size()) {
    const bool a_longer = a.records.size() > b.records.size();
    const DecodedRecord& r = a_longer ? a.records[n] : b.records[n];
    mark_record(&d, r, r.generation);
    d.missing_in_b = a_longer;
    d.missing_in_a = !a_longer;
  }
  return d;
}

}  // namespace tandem
