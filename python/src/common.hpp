// Shared helpers of the Python module packlab._core (pybind11): NumPy views of the C++
// arrays without copies, moving result vectors into NumPy arrays, the throttled progress
// callback that re-acquires the GIL, and conversions of small vectors.
#pragma once

#include <fmt/format.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "packlab/core/error.hpp"
#include "packlab/core/vec3.hpp"
#include "packlab/io/config.hpp"

namespace py = pybind11;

namespace packlab::python {

static_assert(sizeof(Vec3) == 3 * sizeof(double) && std::is_standard_layout_v<Vec3>,
              "Vec3 must be three contiguous doubles to be viewed as an N x 3 array");
static_assert(sizeof(std::array<int, 3>) == 3 * sizeof(int));

inline void make_read_only(py::array& a) { a.attr("setflags")(py::arg("write") = false); }

// A 1-D NumPy view of v; `owner` (the Python object that owns v) is kept alive by the array.
// The view is valid until the vector is resized (the particle count changes).
template <class T>
py::array view(std::vector<T>& v, py::handle owner, bool writeable = true) {
  py::array a =
      py::array_t<T>({static_cast<py::ssize_t>(v.size())}, {static_cast<py::ssize_t>(sizeof(T))}, v.data(), owner);
  if (!writeable) make_read_only(a);
  return a;
}

// An N x 3 float64 view of a vector of Vec3.
inline py::array view(std::vector<Vec3>& v, py::handle owner, bool writeable = true) {
  py::array a = py::array_t<double>({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}},
                                    {static_cast<py::ssize_t>(sizeof(Vec3)), static_cast<py::ssize_t>(sizeof(double))},
                                    reinterpret_cast<double*>(v.data()), owner);
  if (!writeable) make_read_only(a);
  return a;
}

// An N x 3 int32 view of a vector of std::array<int, 3> (bond images).
inline py::array view(std::vector<std::array<int, 3>>& v, py::handle owner, bool writeable = true) {
  py::array a = py::array_t<int>({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}},
                                 {static_cast<py::ssize_t>(3 * sizeof(int)), static_cast<py::ssize_t>(sizeof(int))},
                                 reinterpret_cast<int*>(v.data()), owner);
  if (!writeable) make_read_only(a);
  return a;
}

// A bool view of a vector of 0/1 bytes (fixed flags, rattlers).
inline py::array bool_view(std::vector<std::uint8_t>& v, py::handle owner, bool writeable = true) {
  py::array a(py::dtype("bool"), {static_cast<py::ssize_t>(v.size())}, {py::ssize_t{1}}, v.data(), owner);
  if (!writeable) make_read_only(a);
  return a;
}

// Moves a result vector into a NumPy array that owns it (no copy of the elements).
template <class T>
py::array to_numpy(std::vector<T>&& v) {
  auto* heap = new std::vector<T>(std::move(v));
  py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return view(*heap, owner);
}
inline py::array to_numpy_bool(std::vector<std::uint8_t>&& v) {
  auto* heap = new std::vector<std::uint8_t>(std::move(v));
  py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<std::uint8_t>*>(p); });
  return bool_view(*heap, owner);
}

// `values` as a NumPy array whose dtype kind is one of `kinds` ('f' float, 'i'/'u' integer,
// 'b' bool); packlab.InputError naming `what` otherwise (None, strings, objects, complex, or an
// integer array given floats), so that a wrong type is never cast silently.
inline py::array numeric_array(const py::handle& values, const char* what, std::string_view kinds,
                               std::string_view expected) {
  py::array a;
  try {
    a = py::module_::import("numpy").attr("asarray")(values);
  } catch (const py::error_already_set&) {
    fail_input(fmt::format("{}: must be {}, got {}", what, expected, std::string(py::repr(values)).substr(0, 60)));
  }
  const std::string kind = py::str(a.dtype().attr("kind"));
  if (kind.size() != 1 || kinds.find(kind[0]) == std::string_view::npos) {
    const std::string got =
        values.is_none() ? std::string("None") : fmt::format("dtype {}", std::string(py::str(a.dtype())));
    fail_input(fmt::format("{}: must be {}, got {}", what, expected, got));
  }
  return a;
}

// Copies an array-like into a vector of n elements (n < 0: any length); packlab.InputError
// naming `what` on a wrong shape or type. Integer targets take integer (or bool) arrays only,
// in the target's range; float targets take float or integer arrays.
template <class T>
std::vector<T> from_numpy(const py::handle& values, const char* what, py::ssize_t n = -1) {
  constexpr bool integral = std::is_integral_v<T>;
  const char* expected = std::is_same_v<T, bool> ? "a 1-D array of booleans (or 0/1 integers)"
                         : integral              ? "a 1-D array of integers"
                                                 : "a 1-D array of numbers";
  const py::array raw = numeric_array(values, what, integral ? "iub" : "fiu", expected);
  if (raw.ndim() != 1) fail_input(fmt::format("{}: must be {}, got {} dimensions", what, expected, raw.ndim()));
  if (n >= 0 && raw.shape(0) != n) fail_input(fmt::format("{}: must have {} entries, got {}", what, n, raw.shape(0)));
  if constexpr (integral && !std::is_same_v<T, bool>) {
    // Through int64 (exact for every integer dtype but huge uint64), then a range check.
    auto a = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(raw);
    if (!a) fail_input(fmt::format("{}: must be {}", what, expected));
    std::vector<T> out(static_cast<std::size_t>(a.shape(0)));
    for (py::ssize_t k = 0; k < a.shape(0); ++k) {
      const long long v = a.at(k);
      if (v < static_cast<long long>(std::numeric_limits<T>::min()) ||
          v > static_cast<long long>(std::numeric_limits<T>::max()))
        fail_input(fmt::format("{}[{}] = {}: must be in [{}, {}]", what, k, v, std::numeric_limits<T>::min(),
                               std::numeric_limits<T>::max()));
      out[static_cast<std::size_t>(k)] = static_cast<T>(v);
    }
    return out;
  } else {
    auto a = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(raw);
    if (!a) fail_input(fmt::format("{}: must be {}", what, expected));
    return std::vector<T>(a.data(), a.data() + a.shape(0));
  }
}

inline std::vector<Vec3> vec3s_from_numpy(const py::handle& values, const char* what, py::ssize_t n = -1) {
  const py::array raw = numeric_array(values, what, "fiu", "an N x 3 array of numbers");
  if (raw.ndim() != 2 || raw.shape(1) != 3) {
    std::string shape;
    for (py::ssize_t d = 0; d < raw.ndim(); ++d) shape += fmt::format("{}{}", d ? " x " : "", raw.shape(d));
    fail_input(fmt::format("{}: must be an N x 3 array, got shape ({})", what, shape));
  }
  if (n >= 0 && raw.shape(0) != n) fail_input(fmt::format("{}: must have {} rows, got {}", what, n, raw.shape(0)));
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(raw);
  if (!a) fail_input(fmt::format("{}: must be an N x 3 array of numbers", what));
  std::vector<Vec3> out(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t k = 0; k < a.shape(0); ++k) out[static_cast<std::size_t>(k)] = {a.at(k, 0), a.at(k, 1), a.at(k, 2)};
  return out;
}

inline Vec3 to_vec3(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
inline std::array<double, 3> from_vec3(const Vec3& v) { return {v.x, v.y, v.z}; }

// A types.SimpleNamespace of the entries of `values` (what the generators and analyses return).
inline py::object namespace_of(py::dict values) {
  return py::module_::import("types").attr("SimpleNamespace")(**values);
}

// Applies keyword arguments to the targets of an option set (io/config.hpp): each keyword is a
// key with `_` for `.` (relax_max_steps for relax.max_steps) or an alias; the value goes through
// the same checks as a config-file value. An unknown keyword or a value of the wrong type raises
// packlab.InputError naming `function` and the keyword. Defaults stay those of the struct.
// Returns the schema (e.g. for validate()).
inline io::ConfigSchema apply_keywords(io::ConfigSchema schema, const py::kwargs& kwargs, const std::string& function) {
  for (const auto& [name_handle, value_handle] : kwargs) {
    const std::string name = py::str(name_handle);
    const auto value = py::reinterpret_borrow<py::object>(value_handle);
    const io::ConfigSchema::Field* field = schema.find(name);
    if (field == nullptr || !field->python || name.find('.') != std::string::npos || name.rfind("--", 0) == 0) {
      std::string known;
      for (const std::string& k : schema.keywords()) known += (known.empty() ? "" : ", ") + k;
      fail_input(function + ": unknown keyword '" + name + "' (known: " + known + ")");
    }
    io::ConfigSchema::Value v;
    if (field->type == "numbers" && !py::isinstance<py::str>(value))
      v = from_numpy<double>(value, name.c_str());
    else if (py::isinstance<py::bool_>(value) || py::isinstance(value, py::module_::import("numpy").attr("bool_")))
      v = value.cast<bool>();
    else if (py::isinstance<py::str>(value))
      v = value.cast<std::string>();
    else if (py::hasattr(value, "__index__")) {
      // Python integers have no bound: one beyond int64 (seed=2**64) is out of every integer
      // key's range, said as the command line says it (not pybind11's cast error).
      const py::int_ integer(value);
      try {
        v = integer.cast<std::int64_t>();
      } catch (const py::cast_error&) {
        fail_input(fmt::format("{} = {}: out of range", name, std::string(py::repr(integer))));
      }
    } else if (py::hasattr(value, "__float__"))
      v = value.cast<double>();
    else
      fail_input(function + ": " + name + " = " + std::string(py::repr(value)) + ": must be a " + field->type);
    io::ConfigSchema::set(*field, v, name);
  }
  return schema;
}

// A JSON value (a report block, io/mechanics_report.hpp) as Python objects: the dicts the
// functions return carry the same keys as the command's report.json.
inline py::object json_to_python(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

// The keyword list of a docstring: one line per option of the set.
inline std::string keywords_doc(const io::ConfigSchema& schema) { return "Keywords:\n" + schema.python_doc(); }

// The optional progress callback of long runs. The run itself holds no GIL; every call of
// tick() (from the thread that released it) re-acquires the GIL, checks for Ctrl-C and calls
// the callback at most every `interval` seconds (always when `force`). A Python exception in
// the callback (or KeyboardInterrupt) stops the run and propagates.
class ProgressCallback {
 public:
  ProgressCallback(py::object callback, double interval) : callback_(std::move(callback)), interval_(interval) {}

  template <class... Args>
  void tick(bool force, Args&&... args) {
    const auto now = std::chrono::steady_clock::now();
    const bool due = force || !called_ || std::chrono::duration<double>(now - last_).count() >= interval_;
    const bool signal_due = std::chrono::duration<double>(now - last_signal_check_).count() >= 0.05;
    if (!(due && !callback_.is_none()) && !signal_due) return;
    py::gil_scoped_acquire gil;
    if (signal_due) {
      last_signal_check_ = now;
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
    if (due && !callback_.is_none()) {
      called_ = true;
      last_ = now;
      callback_(std::forward<Args>(args)...);
    }
  }

 private:
  py::object callback_;
  double interval_;
  bool called_ = false;
  std::chrono::steady_clock::time_point last_{}, last_signal_check_{};
};

// One function per concern, in the file of the same name (python/src mirrors src/packlab).
void bind_packing(py::module_& m);
void bind_io(py::module_& m);
void bind_generate(py::module_& m);           // generate.cpp: lattice, random, bond
void bind_generate_vem(py::module_& m);       // generate_vem.cpp
void bind_generate_ls(py::module_& m);        // generate_ls.cpp
void bind_generate_shake(py::module_& m);     // generate_shake.cpp
void bind_generate_scrm(py::module_& m);      // generate_scrm.cpp
void bind_analyze(py::module_& m);            // analyze.cpp: coordination, porosity, density
void bind_analyze_rdf(py::module_& m);        // analyze_rdf.cpp
void bind_analyze_pore_size(py::module_& m);  // analyze_pore_size.cpp
void bind_analyze_fabric(py::module_& m);     // analyze_fabric.cpp
void bind_analyze_fits(py::module_& m);       // analyze_fits.cpp: inflection, power law, porosity laws
void bind_dem(py::module_& m);
void bind_oscillatory_shear(py::module_& m);     // oscillatory_shear.cpp, its calibration
void bind_generate_fba(py::module_& m);          // generate_fba.cpp
void bind_generate_bd(py::module_& m);           // generate_bd.cpp
void bind_generate_opal(py::module_& m);         // generate_opal.cpp: inverse-opal builder
void bind_uniaxial_compression(py::module_& m);  // uniaxial_compression.cpp, its calibration

}  // namespace packlab::python
