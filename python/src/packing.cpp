// packlab.Box, packlab.Bonds, packlab.Packing: the shared data type with its arrays as NumPy
// views (no copies). While a view of an array is alive, nothing may move that array's storage:
// adding particles or bonds, replacing the bond list, removing an optional array or a field
// raise packlab.InputError instead (as NumPy refuses to resize an array that is referenced),
// so a view can never point to freed memory.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "common.hpp"
#include "packlab/core/packing.hpp"

namespace packlab::python {

namespace {

// Live views per storage block (a vector's data()); only touched with the GIL held (views are
// created by Python calls and released by Python's deallocation of their base capsule).
std::unordered_map<const void*, std::size_t>& live_views() {
  static auto* views = new std::unordered_map<const void*, std::size_t>();  // never destroyed: capsules may outlive statics
  return *views;
}

// The base object of a view of `v`: keeps `owner` (the Python object holding v) alive and counts
// the view as live until NumPy drops it (views of views keep it too).
template <class T>
py::object pin(std::vector<T>& v, py::handle owner) {
  struct Pin {
    const void* storage;
    py::object owner;
  };
  auto* held = new Pin{v.data(), py::reinterpret_borrow<py::object>(owner)};
  ++live_views()[held->storage];
  return py::capsule(held, [](void* raw) {
    auto* p = static_cast<Pin*>(raw);
    auto& views = live_views();
    if (const auto at = views.find(p->storage); at != views.end() && --at->second == 0) views.erase(at);
    delete p;
  });
}

template <class T>
py::array pinned_view(std::vector<T>& v, py::handle owner) {
  if (v.empty()) return view(v, owner);  // no storage that could move under it
  return view(v, pin(v, owner));
}
py::array pinned_bool_view(std::vector<std::uint8_t>& v, py::handle owner) {
  if (v.empty()) return bool_view(v, owner);
  return bool_view(v, pin(v, owner));
}

// InputError when a NumPy view of `v` is alive, before an operation that may move or free v's
// storage (`what` names the operation and the array).
template <class T>
void require_no_views(const std::vector<T>& v, std::string_view what) {
  if (v.capacity() == 0) return;
  const auto at = live_views().find(v.data());
  if (at == live_views().end()) return;
  fail_input(fmt::format("{}: {} NumPy view(s) of this array are alive (e.g. x = p.positions); the operation "
                         "would move the memory they point to. Delete them (del x) or keep copies "
                         "(x = p.positions.copy()) first",
                         what, at->second));
}

void require_no_bond_views(const Bonds& b, std::string_view what) {
  require_no_views(b.i, what);
  require_no_views(b.j, what);
  require_no_views(b.image, what);
  require_no_views(b.material, what);
  require_no_views(b.rest_length, what);
  require_no_views(b.state, what);
}

// Copies into the existing storage when the size matches, so that views taken before stay
// valid and see the new values; otherwise (an absent optional array) replaces it.
template <class T>
void assign_in_place(std::vector<T>& target, std::vector<T>&& values, std::string_view what) {
  if (target.size() == values.size()) {
    std::copy(values.begin(), values.end(), target.begin());
  } else {
    require_no_views(target, what);
    target = std::move(values);
  }
}

// Removes an optional array, freeing its storage once no view uses it.
template <class T>
void remove_array(std::vector<T>& target, std::string_view what) {
  require_no_views(target, what);
  std::vector<T>().swap(target);
}

void require_finite(const std::vector<Vec3>& values, const char* what) {
  for (std::size_t k = 0; k < values.size(); ++k) {
    const Vec3& v = values[k];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      fail_input(fmt::format("{}[{}] = ({:g}, {:g}, {:g}): must be finite", what, k, v.x, v.y, v.z));
  }
}

void require_positive(const std::vector<double>& values, const char* what) {
  for (std::size_t k = 0; k < values.size(); ++k)
    if (!(values[k] > 0.0) || !std::isfinite(values[k]))
      fail_input(fmt::format("{}[{}] = {:g}: must be positive and finite", what, k, values[k]));
}

void require_non_negative(const std::vector<int>& values, const char* what) {
  for (std::size_t k = 0; k < values.size(); ++k)
    if (values[k] < 0) fail_input(fmt::format("{}[{}] = {}: must be >= 0", what, k, values[k]));
}

std::vector<Vec3> finite_vec3s(py::handle values, const char* what, py::ssize_t n = -1) {
  auto out = vec3s_from_numpy(values, what, n);
  require_finite(out, what);
  return out;
}

std::vector<double> positive_doubles(py::handle values, const char* what, py::ssize_t n = -1) {
  auto out = from_numpy<double>(values, what, n);
  require_positive(out, what);
  return out;
}

std::vector<int> particle_types(py::handle values, const char* what, py::ssize_t n = -1) {
  auto out = from_numpy<int>(values, what, n);
  require_non_negative(out, what);
  return out;
}

// One (x, y, z) of finite numbers.
Vec3 finite_vec3(py::handle value, const char* what) {
  const py::array raw = numeric_array(value, what, "fiu", "three numbers (x, y, z)");
  if (raw.ndim() != 1 || raw.shape(0) != 3)
    fail_input(fmt::format("{}: must be three numbers (x, y, z), got {}", what,
                           std::string(py::repr(value)).substr(0, 60)));
  const auto xyz = from_numpy<double>(raw, what, 3);
  const Vec3 v{xyz[0], xyz[1], xyz[2]};
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    fail_input(fmt::format("{} = ({:g}, {:g}, {:g}): must be finite", what, v.x, v.y, v.z));
  return v;
}

Box make_box(py::object length, py::object lo, std::array<bool, 3> periodic) {
  Box b;
  b.length = finite_vec3(length, "length");
  b.lo = finite_vec3(lo, "lo");
  for (int a = 0; a < 3; ++a)
    if (!(b.length[a] > 0.0))
      fail_input(fmt::format("length along {} = {:g}: must be positive and finite", "xyz"[a], b.length[a]));
  b.periodic = periodic;
  return b;
}

py::tuple tuple3(const Vec3& v) { return py::make_tuple(v.x, v.y, v.z); }

// Optional per-particle arrays: None when absent, a view otherwise; assigning None removes them.
template <class T>
py::object optional_view(std::vector<T>& v, py::handle owner) {
  if (v.empty()) return py::none();
  return pinned_view(v, owner);
}

// Makes `b` the bond list of `p` when its indices, self-bonds and duplicates pass
// Packing::validate_bonds(); leaves p unchanged otherwise.
void replace_bonds(Packing& p, Bonds b) {
  require_no_bond_views(p.bonds, "bonds");
  std::swap(p.bonds, b);
  try {
    p.validate_bonds();
  } catch (const InputError&) {
    std::swap(p.bonds, b);
    throw;
  }
}

void set_bonds(Packing& p, py::object i, py::object j, py::object image, py::object material,
               py::object rest_length, py::object state) {
  Bonds b;
  b.i = from_numpy<int>(i, "i");
  const auto m = static_cast<py::ssize_t>(b.i.size());
  b.j = from_numpy<int>(j, "j", m);
  for (std::size_t k = 0; k < b.i.size(); ++k)
    if (b.i[k] < 0 || b.j[k] < 0 || static_cast<std::size_t>(b.i[k]) >= p.size() ||
        static_cast<std::size_t>(b.j[k]) >= p.size())
      fail_input(fmt::format("bond {} joins particles {} and {}: indices must be in [0, {})", k, b.i[k], b.j[k],
                             p.size()));
  if (image.is_none()) {
    b.image.assign(b.i.size(), {0, 0, 0});
  } else {
    const py::array raw = numeric_array(image, "image", "iu", "an M x 3 array of integers");
    if (raw.ndim() != 2 || raw.shape(1) != 3 || raw.shape(0) != m)
      fail_input(fmt::format("image: must be an M x 3 integer array with M = {}", m));
    const auto flat = from_numpy<int>(raw.attr("reshape")(-1), "image");
    b.image.resize(b.i.size());
    for (std::size_t k = 0; k < b.image.size(); ++k) b.image[k] = {flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]};
  }
  b.material = material.is_none() ? std::vector<int>(b.i.size(), 0) : from_numpy<int>(material, "material", m);
  if (rest_length.is_none()) {
    // Current length of the bond vector r_j + image L - r_i.
    b.rest_length.resize(b.i.size());
    for (std::size_t k = 0; k < b.i.size(); ++k)
      b.rest_length[k] =
          norm(p.position[static_cast<std::size_t>(b.j[k])] + p.box.shift_vector(b.image[k]) -
               p.position[static_cast<std::size_t>(b.i[k])]);
  } else {
    b.rest_length = from_numpy<double>(rest_length, "rest_length", m);
  }
  b.state = state.is_none() ? std::vector<int>(b.i.size(), 0) : from_numpy<int>(state, "state", m);
  try {
    replace_bonds(p, std::move(b));
  } catch (const InputError& error) {
    const std::string message = error.what();
    // The common way to get there: contacts of a small periodic box passed without their images.
    if (image.is_none() && message.find("bonded at most once") != std::string::npos)
      fail_input(fmt::format("{} (in a periodic box a pair can touch through several images: pass image=, "
                             "e.g. from find_contacts' branch vectors)",
                             message));
    throw;
  }
}

}  // namespace

void bind_packing(py::module_& m) {
  py::class_<Box>(m, "Box", R"doc(
The simulation box: an axis-aligned cuboid [lo, lo + length), periodic or not per axis.

Box(length=(1, 1, 1), lo=(0, 0, 0), periodic=(True, True, True)); lengths in [m].
)doc")
      .def(py::init(&make_box), py::arg("length") = py::make_tuple(1.0, 1.0, 1.0),
           py::arg("lo") = py::make_tuple(0.0, 0.0, 0.0), py::arg("periodic") = std::array<bool, 3>{true, true, true})
      .def_property(
          "lo", [](const Box& b) { return tuple3(b.lo); },
          [](Box& b, py::object v) { b.lo = make_box(tuple3(b.length), v, b.periodic).lo; },
          "Lower corner (x, y, z) [m].")
      .def_property(
          "length", [](const Box& b) { return tuple3(b.length); },
          [](Box& b, py::object v) { b.length = make_box(v, tuple3(b.lo), b.periodic).length; },
          "Edge lengths (Lx, Ly, Lz) [m].")
      .def_property(
          "periodic", [](const Box& b) { return py::make_tuple(b.periodic[0], b.periodic[1], b.periodic[2]); },
          [](Box& b, std::array<bool, 3> v) { b.periodic = v; }, "Periodicity per axis (x, y, z).")
      .def_property_readonly("hi", [](const Box& b) { return tuple3(b.hi()); }, "Upper corner lo + length [m].")
      .def_property_readonly("volume", &Box::volume, "Box volume [m^3].")
      .def(
          "minimum_image", [](const Box& b, std::array<double, 3> d) { return tuple3(b.minimum_image(to_vec3(d))); },
          py::arg("d"), "Shortest periodic image of the separation d = r_j - r_i.")
      .def("__repr__", [](const Box& b) {
        return fmt::format("Box(length=({:g}, {:g}, {:g}), lo=({:g}, {:g}, {:g}), periodic=({}, {}, {}))", b.length.x,
                           b.length.y, b.length.z, b.lo.x, b.lo.y, b.lo.z, b.periodic[0] ? "True" : "False",
                           b.periodic[1] ? "True" : "False", b.periodic[2] ? "True" : "False");
      });

  py::class_<Bonds>(m, "Bonds", R"doc(
The bond list of a bonded model as parallel arrays (NumPy views, no copies): bond k joins
particle i[k] to the periodic image image[k] of particle j[k] (the bond vector is
r_j + image * L - r_i), with a material index, a rest length [m] and a state (0 intact,
1 broken). While a view of these arrays is alive, add() and replacing the bond list raise
InputError (they would move the memory the view points to): drop the views or copy them first.
)doc")
      .def(py::init<>())
      .def("__len__", &Bonds::size)
      .def_property_readonly("i", [](py::object self) { return pinned_view(self.cast<Bonds&>().i, self); }, "First particle.")
      .def_property_readonly("j", [](py::object self) { return pinned_view(self.cast<Bonds&>().j, self); }, "Second particle.")
      .def_property_readonly(
          "image", [](py::object self) { return pinned_view(self.cast<Bonds&>().image, self); },
          "M x 3 periodic image of j (in box lengths).")
      .def_property_readonly(
          "material", [](py::object self) { return pinned_view(self.cast<Bonds&>().material, self); }, "Bond material index.")
      .def_property_readonly(
          "rest_length", [](py::object self) { return pinned_view(self.cast<Bonds&>().rest_length, self); },
          "Initial (rest) length [m].")
      .def_property_readonly(
          "state", [](py::object self) { return pinned_view(self.cast<Bonds&>().state, self); }, "0 intact, 1 broken.")
      .def(
          "add",
          [](Bonds& b, int i, int j, std::array<int, 3> image, int material, double rest_length, int state) {
            if (i < 0 || j < 0) fail_input(fmt::format("add: bond joins particles {} and {}: indices must be >= 0", i, j));
            if (i == j && image == std::array<int, 3>{0, 0, 0})
              fail_input(fmt::format("add: bond joins particle {} to itself (image 0 0 0): a bond needs two particles", i));
            if (!std::isfinite(rest_length) || rest_length < 0.0)
              fail_input(fmt::format("add: rest_length = {:g}: must be finite and >= 0", rest_length));
            require_no_bond_views(b, "Bonds.add");
            b.add(i, j, image, material, rest_length, state);
          },
          py::arg("i"), py::arg("j"), py::arg("image") = std::array<int, 3>{0, 0, 0}, py::arg("material") = 0,
          py::arg("rest_length"), py::arg("state") = 0, "Appends one bond.")
      .def("__repr__", [](const Bonds& b) { return fmt::format("<packlab.Bonds: {} bonds>", b.size()); });

  py::class_<Packing>(m, "Packing", R"doc(
A packing: a box and, per particle, position [m], radius [m] and type (0 structural, 1 void,
2 pore, 3 coating, 4 substrate), optionally velocity [m/s], angular velocity [rad/s], density
[kg/m^3] and a fixed flag, extra named scalar fields and a bond list.

The arrays are NumPy views of the C++ storage (no copies): modifying ``p.positions[...]``
changes the packing. Assigning a whole array (``p.radii = r``) copies it in place and needs
one entry per particle. While a view is alive, operations that would move its memory
(``add``, removing an optional array) raise InputError: drop the view (``del x``) or work on a
copy (``p.positions.copy()``). Optional arrays (velocities, angular_velocities, densities,
fixed) are None when absent; assign an array to add them and None to remove them. Arrays are
checked on assignment: shape, dtype (integers for types and bond indices), finite values,
positive radii and densities, types >= 0; errors raise InputError.

Packing(positions=None, radii=None, types=None, box=None): positions N x 3, radii N, types N
(default 0); box defaults to the unit periodic cube.
)doc")
      .def(py::init([](py::object positions, py::object radii, py::object types, std::optional<Box> box) {
             Packing p;
             if (box) p.box = *box;
             if (positions.is_none() && !(radii.is_none() && types.is_none()))
               fail_input("positions: required with radii or types (an N x 3 array of numbers), got None");
             if (!positions.is_none()) p.position = finite_vec3s(positions, "positions");
             const auto n = static_cast<py::ssize_t>(p.position.size());
             if (!radii.is_none()) p.radius = positive_doubles(radii, "radii", n);
             else if (n > 0) fail_input("radii: required with positions (one radius per particle), got None");
             p.type = types.is_none() ? std::vector<int>(p.position.size(), 0) : particle_types(types, "types", n);
             return p;
           }),
           py::arg("positions") = py::none(), py::arg("radii") = py::none(), py::arg("types") = py::none(),
           py::arg("box") = py::none())
      .def("__len__", &Packing::size)
      .def("__copy__", [](const Packing& p) { return Packing(p); })
      .def("__deepcopy__", [](const Packing& p, py::dict) { return Packing(p); }, py::arg("memo"))
      .def("copy", [](const Packing& p) { return Packing(p); }, "An independent copy (arrays copied).")
      .def_readwrite("box", &Packing::box, "The Box (a reference: p.box.length = ... changes the packing).")
      .def_property(
          "positions", [](py::object self) { return pinned_view(self.cast<Packing&>().position, self); },
          [](Packing& p, py::object v) {
            assign_in_place(p.position, finite_vec3s(v, "positions", static_cast<py::ssize_t>(p.size())), "positions");
          },
          "N x 3 float64 view of the centres [m].")
      .def_property(
          "radii", [](py::object self) { return pinned_view(self.cast<Packing&>().radius, self); },
          [](Packing& p, py::object v) {
            assign_in_place(p.radius, positive_doubles(v, "radii", static_cast<py::ssize_t>(p.size())), "radii");
          },
          "N float64 view of the radii [m].")
      .def_property(
          "types", [](py::object self) { return pinned_view(self.cast<Packing&>().type, self); },
          [](Packing& p, py::object v) {
            assign_in_place(p.type, particle_types(v, "types", static_cast<py::ssize_t>(p.size())), "types");
          },
          "N int32 view of the particle types.")
      .def_property(
          "velocities", [](py::object self) { return optional_view(self.cast<Packing&>().velocity, self); },
          [](Packing& p, py::object v) {
            if (v.is_none()) remove_array(p.velocity, "velocities = None");
            else
              assign_in_place(p.velocity, finite_vec3s(v, "velocities", static_cast<py::ssize_t>(p.size())),
                              "velocities");
          },
          "N x 3 view of the velocities [m/s], or None.")
      .def_property(
          "angular_velocities",
          [](py::object self) { return optional_view(self.cast<Packing&>().angular_velocity, self); },
          [](Packing& p, py::object v) {
            if (v.is_none())
              remove_array(p.angular_velocity, "angular_velocities = None");
            else
              assign_in_place(p.angular_velocity,
                              finite_vec3s(v, "angular_velocities", static_cast<py::ssize_t>(p.size())),
                              "angular_velocities");
          },
          "N x 3 view of the angular velocities [rad/s], or None.")
      .def_property(
          "densities", [](py::object self) { return optional_view(self.cast<Packing&>().density, self); },
          [](Packing& p, py::object v) {
            if (v.is_none())
              remove_array(p.density, "densities = None");
            else
              assign_in_place(p.density, positive_doubles(v, "densities", static_cast<py::ssize_t>(p.size())),
                              "densities");
          },
          "N view of the densities [kg/m^3], or None.")
      .def_property(
          "fixed",
          [](py::object self) -> py::object {
            auto& f = self.cast<Packing&>().fixed;
            if (f.empty()) return py::none();
            return pinned_bool_view(f, self);
          },
          [](Packing& p, py::object v) {
            if (v.is_none()) {
              remove_array(p.fixed, "fixed = None");
              return;
            }
            const auto flags = from_numpy<bool>(v, "fixed", static_cast<py::ssize_t>(p.size()));
            assign_in_place(p.fixed, std::vector<std::uint8_t>(flags.begin(), flags.end()), "fixed");
          },
          "N bool view of the fixed flags (True = does not move), or None.")
      .def_property(
          "bonds", [](Packing& p) -> Bonds& { return p.bonds; }, [](Packing& p, const Bonds& b) { replace_bonds(p, b); },
          py::return_value_policy::reference_internal, "The bond list (Bonds, a reference).")
      .def(
          "set_bonds", &set_bonds, py::arg("i"), py::arg("j"), py::arg("image") = py::none(),
          py::arg("material") = py::none(), py::arg("rest_length") = py::none(), py::arg("state") = py::none(),
          R"doc(Replaces the bond list from arrays. image defaults to (0, 0, 0), material and state to 0,
rest_length to the current length |r_j + image * L - r_i| of each bond [m].)doc")
      .def(
          "add",
          [](Packing& p, py::object position, double radius, int type) {
            if (!p.velocity.empty() || !p.angular_velocity.empty() || !p.density.empty() || !p.fixed.empty() ||
                !p.fields.empty())
              fail_input("add: only for packings without optional arrays or fields (build the arrays "
                         "with NumPy and make a new Packing instead)");
            const Vec3 at = finite_vec3(position, "add: position");
            if (!(radius > 0.0) || !std::isfinite(radius))
              fail_input(fmt::format("add: radius = {:g}: must be positive and finite", radius));
            if (type < 0) fail_input(fmt::format("add: type = {}: must be >= 0", type));
            require_no_views(p.position, "add");
            require_no_views(p.radius, "add");
            require_no_views(p.type, "add");
            p.add(at, radius, type);
          },
          py::arg("position"), py::arg("radius"), py::arg("type") = 0,
          "Appends one particle. Raises InputError while a view of positions, radii or types is alive "
          "(appending may move their memory).")
      .def("volume_fraction", &Packing::volume_fraction,
           "Sum of sphere volumes over the box volume (overlaps counted twice).")
      .def("validate", &Packing::validate,
           "Raises InputError naming the first inconsistency (sizes, negative radius, NaN, bond index, box).")
      .def_property_readonly(
          "field_names",
          [](const Packing& p) {
            std::vector<std::string> names;
            for (const auto& f : p.fields) names.push_back(f.name);
            return names;
          },
          "Names of the extra per-particle scalar fields.")
      .def(
          "field",
          [](py::object self, const std::string& name) {
            auto& p = self.cast<Packing&>();
            for (auto& f : p.fields)
              if (f.name == name) return pinned_view(f.values, self);
            throw py::key_error(fmt::format("field '{}': not in this packing", name));
          },
          py::arg("name"), "View of the extra scalar field `name` (KeyError if absent).")
      .def(
          "set_field",
          [](Packing& p, const std::string& name, py::object values) {
            auto v = from_numpy<double>(values, name.c_str(), static_cast<py::ssize_t>(p.size()));
            assign_in_place(p.field_or_add(name).values, std::move(v), name);
          },
          py::arg("name"), py::arg("values"), "Adds or replaces the extra scalar field `name` (one value per particle).")
      .def(
          "remove_field",
          [](Packing& p, const std::string& name) {
            for (const auto& f : p.fields)
              if (f.name == name) require_no_views(f.values, fmt::format("remove_field('{}')", name));
            std::erase_if(p.fields, [&](const ScalarField& f) { return f.name == name; });
          },
          py::arg("name"))
      .def("__repr__", [](const Packing& p) {
        return fmt::format("<packlab.Packing: {} particles, {} bonds, box {:g} x {:g} x {:g}>", p.size(),
                           p.bonds.size(), p.box.length.x, p.box.length.y, p.box.length.z);
      });
}

}  // namespace packlab::python
