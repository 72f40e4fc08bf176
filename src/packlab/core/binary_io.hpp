// Little helpers for binary checkpoints: trivially copyable values and vectors of them, with
// sizes checked on reading so a truncated or foreign file gives an InputError, not a crash.
#pragma once

#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <type_traits>
#include <vector>

#include "packlab/core/error.hpp"

namespace packlab::binary {

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
  if (!v.empty()) out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
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

inline void read_string(std::istream& in, std::string& s, const char* what) {
  std::vector<char> chars;
  read_vector(in, chars, what, 4096);
  s.assign(chars.begin(), chars.end());
}

}  // namespace packlab::binary
