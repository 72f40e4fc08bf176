// Little helpers for binary checkpoints: trivially copyable values and vectors of them, with
// sizes checked on reading so a truncated or foreign file gives an InputError, not a crash.
#pragma once

#include <cstdint>
#include <istream>
#include <ostream>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "packlab/core/error.hpp"
#include "packlab/core/random.hpp"

namespace packlab::binary {

// A checkpoint's eight-byte tag as text where it is printable (e.g. "PDEMECK4"), else in hex.
inline std::string header_tag(std::uint64_t magic) {
  std::string text;
  bool printable = true;
  for (int b = 0; b < 8; ++b) {
    const char c = static_cast<char>((magic >> (8 * b)) & 0xFF);
    printable = printable && c >= 0x20 && c < 0x7F;
    text += c;
  }
  if (printable) return text;
  static constexpr char digits[] = "0123456789abcdef";
  std::string hex = "0x";
  for (int b = 15; b >= 0; --b) hex += digits[(magic >> (4 * b)) & 0xF];
  return hex;
}

// InputError unless `found` is the `expected` tag: "<refusal> of this version (header X, this
// version writes and reads Y)" and what to do about another version's state.
inline void require_header(std::uint64_t found, std::uint64_t expected, const std::string& refusal) {
  if (found == expected) return;
  fail_input(refusal + " of this version (header " + header_tag(found) + ", this version writes and reads " +
             header_tag(expected) +
             "): start the run again without resuming, or resume it with the version that "
             "wrote it");
}

template <class T>
void write(std::ostream& out, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <class T>
void read(std::istream& in, T& value, const char* what) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (!in.read(reinterpret_cast<char*>(&value), sizeof(T)))
    fail_input(std::string("checkpoint is truncated while reading ") + what);
}

template <class T>
void write_vector(std::ostream& out, const std::vector<T>& v) {
  static_assert(std::is_trivially_copyable_v<T>);
  write(out, static_cast<std::uint64_t>(v.size()));
  if (!v.empty())
    out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
}

template <class T>
void read_vector(std::istream& in, std::vector<T>& v, const char* what, std::uint64_t max_size = 1ULL << 34) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::uint64_t n = 0;
  read(in, n, what);
  if (n > max_size) fail_input(std::string("checkpoint is damaged: implausible size of ") + what);
  v.resize(n);
  if (n > 0 && !in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T))))
    fail_input(std::string("checkpoint is truncated while reading ") + what);
}

inline void write_string(std::ostream& out, const std::string& s) {
  write_vector(out, std::vector<char>(s.begin(), s.end()));
}

inline void read_string(std::istream& in, std::string& s, const char* what, std::uint64_t max_size = 4096) {
  std::vector<char> chars;
  read_vector(in, chars, what, max_size);
  s.assign(chars.begin(), chars.end());
}

// The exact state of the random generator (the standard's text form of std::mt19937_64), as
// a vector of characters.
inline void write_random(std::ostream& out, const Random& rng) {
  std::ostringstream text;
  text << rng.engine();
  const std::string s = text.str();
  write_vector(out, std::vector<char>(s.begin(), s.end()));
}

inline void read_random(std::istream& in, Random& rng) {
  std::vector<char> chars;
  read_vector(in, chars, "random generator", 1 << 20);
  std::istringstream text(std::string(chars.begin(), chars.end()));
  text >> rng.engine();
  if (!text) fail_input("checkpoint is damaged: random generator state");
}

// FNV-1a, 64 bit: a checksum against damaged files (not against tampering).
inline std::uint64_t fnv1a(const std::string& bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (unsigned char c : bytes) {
    hash ^= c;
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

// A checksummed section: its size, its hash and the bytes `body` writes. read_checked() gives
// those bytes back only when the hash matches, so a flipped byte is an InputError, never a
// crash or a silently different state.
template <class Body>
void write_checked(std::ostream& out, Body&& body) {
  std::ostringstream section;
  body(static_cast<std::ostream&>(section));
  const std::string bytes = section.str();
  write(out, static_cast<std::uint64_t>(bytes.size()));
  write(out, fnv1a(bytes));
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

inline std::istringstream read_checked(std::istream& in, const char* what, std::uint64_t max_size = 1ULL << 36) {
  std::uint64_t size = 0, hash = 0;
  read(in, size, what);
  read(in, hash, what);
  if (size > max_size) fail_input(std::string("checkpoint is damaged: implausible size of ") + what);
  std::string bytes(size, '\0');
  if (size > 0 && !in.read(bytes.data(), static_cast<std::streamsize>(size)))
    fail_input(std::string("checkpoint is truncated while reading ") + what);
  if (fnv1a(bytes) != hash) fail_input(std::string("checkpoint is damaged: checksum mismatch in ") + what);
  return std::istringstream(std::move(bytes));
}

}  // namespace packlab::binary
