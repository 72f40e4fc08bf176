// packlab.Box, packlab.Bonds, packlab.Packing: the shared data type with its arrays as NumPy
// views (no copies). A view stays valid until the particle (or bond) count changes.
#include <fmt/format.h>

#include <algorithm>

#include "common.hpp"
#include "packlab/core/packing.hpp"

namespace packlab::python {

namespace {

// Copies into the existing storage when the size matches, so that views taken before stay
// valid and see the new values; otherwise (an absent optional array) replaces it.
template <class T>
void assign_in_place(std::vector<T>& target, std::vector<T>&& values) {
  if (target.size() == values.size()) std::copy(values.begin(), values.end(), target.begin());
  else target = std::move(values);
}

py::tuple tuple3(const Vec3& v) { return py::make_tuple(v.x, v.y, v.z); }

// Optional per-particle arrays: None when absent, a view otherwise; assigning None removes them.
template <class T>
py::object optional_view(std::vector<T>& v, py::handle owner) {
  if (v.empty()) return py::none();
  return view(v, owner);
}

void set_bonds(Packing& p, py::object i, py::object j, py::object image, py::object material,
               py::object rest_length, py::object state) {
  Bonds b;
  b.i = from_numpy<int>(i, "i");
  const auto m = static_cast<py::ssize_t>(b.i.size());
  b.j = from_numpy<int>(j, "j", m);
  if (image.is_none()) {
    b.image.assign(b.i.size(), {0, 0, 0});
  } else {
    auto a = py::array_t<int, py::array::c_style | py::array::forcecast>::ensure(image);
    if (!a || a.ndim() != 2 || a.shape(1) != 3 || a.shape(0) != m)
      throw py::value_error(fmt::format("image: must be an M x 3 integer array with M = {}", m));
    b.image.resize(b.i.size());
    for (py::ssize_t k = 0; k < m; ++k)
      b.image[static_cast<std::size_t>(k)] = {a.at(k, 0), a.at(k, 1), a.at(k, 2)};
  }
  b.material = material.is_none() ? std::vector<int>(b.i.size(), 0) : from_numpy<int>(material, "material", m);
  if (rest_length.is_none()) {
    // Current length of the bond vector r_j + image L - r_i.
    b.rest_length.resize(b.i.size());
    for (std::size_t k = 0; k < b.i.size(); ++k) {
      if (b.i[k] < 0 || b.j[k] < 0 || static_cast<std::size_t>(b.i[k]) >= p.size() ||
          static_cast<std::size_t>(b.j[k]) >= p.size())
        throw py::value_error(fmt::format("bond {}: particle index out of range [0, {})", k, p.size()));
      b.rest_length[k] =
          norm(p.position[static_cast<std::size_t>(b.j[k])] + p.box.shift_vector(b.image[k]) -
               p.position[static_cast<std::size_t>(b.i[k])]);
    }
  } else {
    b.rest_length = from_numpy<double>(rest_length, "rest_length", m);
  }
  b.state = state.is_none() ? std::vector<int>(b.i.size(), 0) : from_numpy<int>(state, "state", m);
  p.bonds = std::move(b);
}

}  // namespace

void bind_packing(py::module_& m) {
  py::class_<Box>(m, "Box", R"doc(
The simulation box: an axis-aligned cuboid [lo, lo + length), periodic or not per axis.

Box(length=(1, 1, 1), lo=(0, 0, 0), periodic=(True, True, True)); lengths in [m].
)doc")
      .def(py::init([](std::array<double, 3> length, std::array<double, 3> lo, std::array<bool, 3> periodic) {
             Box b;
             b.length = to_vec3(length);
             b.lo = to_vec3(lo);
             b.periodic = periodic;
             return b;
           }),
           py::arg("length") = std::array<double, 3>{1, 1, 1}, py::arg("lo") = std::array<double, 3>{0, 0, 0},
           py::arg("periodic") = std::array<bool, 3>{true, true, true})
      .def_property(
          "lo", [](const Box& b) { return tuple3(b.lo); },
          [](Box& b, std::array<double, 3> v) { b.lo = to_vec3(v); }, "Lower corner (x, y, z) [m].")
      .def_property(
          "length", [](const Box& b) { return tuple3(b.length); },
          [](Box& b, std::array<double, 3> v) { b.length = to_vec3(v); }, "Edge lengths (Lx, Ly, Lz) [m].")
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
1 broken). Views are valid until the number of bonds changes (add, assignment).
)doc")
      .def(py::init<>())
      .def("__len__", &Bonds::size)
      .def_property_readonly("i", [](py::object self) { return view(self.cast<Bonds&>().i, self); }, "First particle.")
      .def_property_readonly("j", [](py::object self) { return view(self.cast<Bonds&>().j, self); }, "Second particle.")
      .def_property_readonly(
          "image", [](py::object self) { return view(self.cast<Bonds&>().image, self); },
          "M x 3 periodic image of j (in box lengths).")
      .def_property_readonly(
          "material", [](py::object self) { return view(self.cast<Bonds&>().material, self); }, "Bond material index.")
      .def_property_readonly(
          "rest_length", [](py::object self) { return view(self.cast<Bonds&>().rest_length, self); },
          "Initial (rest) length [m].")
      .def_property_readonly(
          "state", [](py::object self) { return view(self.cast<Bonds&>().state, self); }, "0 intact, 1 broken.")
      .def(
          "add",
          [](Bonds& b, int i, int j, std::array<int, 3> image, int material, double rest_length, int state) {
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
one entry per particle; a view stays valid until the particle count changes (``add``).
Optional arrays (velocities, angular_velocities, densities, fixed) are None when absent;
assign an array to add them and None to remove them.

Packing(positions=None, radii=None, types=None, box=None): positions N x 3, radii N, types N
(default 0); box defaults to the unit periodic cube.
)doc")
      .def(py::init([](py::object positions, py::object radii, py::object types, std::optional<Box> box) {
             Packing p;
             if (box) p.box = *box;
             if (!positions.is_none()) p.position = vec3s_from_numpy(positions, "positions");
             const auto n = static_cast<py::ssize_t>(p.position.size());
             if (!radii.is_none()) p.radius = from_numpy<double>(radii, "radii", n);
             else if (n > 0) throw py::value_error("radii: required with positions");
             p.type = types.is_none() ? std::vector<int>(p.position.size(), 0) : from_numpy<int>(types, "types", n);
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
          "positions", [](py::object self) { return view(self.cast<Packing&>().position, self); },
          [](Packing& p, py::object v) {
            assign_in_place(p.position, vec3s_from_numpy(v, "positions", static_cast<py::ssize_t>(p.size())));
          },
          "N x 3 float64 view of the centres [m].")
      .def_property(
          "radii", [](py::object self) { return view(self.cast<Packing&>().radius, self); },
          [](Packing& p, py::object v) {
            assign_in_place(p.radius, from_numpy<double>(v, "radii", static_cast<py::ssize_t>(p.size())));
          },
          "N float64 view of the radii [m].")
      .def_property(
          "types", [](py::object self) { return view(self.cast<Packing&>().type, self); },
          [](Packing& p, py::object v) {
            assign_in_place(p.type, from_numpy<int>(v, "types", static_cast<py::ssize_t>(p.size())));
          },
          "N int32 view of the particle types.")
      .def_property(
          "velocities", [](py::object self) { return optional_view(self.cast<Packing&>().velocity, self); },
          [](Packing& p, py::object v) {
            if (v.is_none()) p.velocity.clear();
            else assign_in_place(p.velocity, vec3s_from_numpy(v, "velocities", static_cast<py::ssize_t>(p.size())));
          },
          "N x 3 view of the velocities [m/s], or None.")
      .def_property(
          "angular_velocities",
          [](py::object self) { return optional_view(self.cast<Packing&>().angular_velocity, self); },
          [](Packing& p, py::object v) {
            if (v.is_none()) p.angular_velocity.clear();
            else
              assign_in_place(p.angular_velocity,
                              vec3s_from_numpy(v, "angular_velocities", static_cast<py::ssize_t>(p.size())));
          },
          "N x 3 view of the angular velocities [rad/s], or None.")
      .def_property(
          "densities", [](py::object self) { return optional_view(self.cast<Packing&>().density, self); },
          [](Packing& p, py::object v) {
            if (v.is_none()) p.density.clear();
            else assign_in_place(p.density, from_numpy<double>(v, "densities", static_cast<py::ssize_t>(p.size())));
          },
          "N view of the densities [kg/m^3], or None.")
      .def_property(
          "fixed",
          [](py::object self) -> py::object {
            auto& f = self.cast<Packing&>().fixed;
            if (f.empty()) return py::none();
            return bool_view(f, self);
          },
          [](Packing& p, py::object v) {
            if (v.is_none()) {
              p.fixed.clear();
              return;
            }
            const auto flags = from_numpy<bool>(v, "fixed", static_cast<py::ssize_t>(p.size()));
            assign_in_place(p.fixed, std::vector<std::uint8_t>(flags.begin(), flags.end()));
          },
          "N bool view of the fixed flags (True = does not move), or None.")
      .def_property(
          "bonds", [](Packing& p) -> Bonds& { return p.bonds; }, [](Packing& p, const Bonds& b) { p.bonds = b; },
          py::return_value_policy::reference_internal, "The bond list (Bonds, a reference).")
      .def(
          "set_bonds", &set_bonds, py::arg("i"), py::arg("j"), py::arg("image") = py::none(),
          py::arg("material") = py::none(), py::arg("rest_length") = py::none(), py::arg("state") = py::none(),
          R"doc(Replaces the bond list from arrays. image defaults to (0, 0, 0), material and state to 0,
rest_length to the current length |r_j + image * L - r_i| of each bond [m].)doc")
      .def(
          "add",
          [](Packing& p, std::array<double, 3> position, double radius, int type) {
            if (!p.velocity.empty() || !p.angular_velocity.empty() || !p.density.empty() || !p.fixed.empty() ||
                !p.fields.empty())
              throw py::value_error("add: only for packings without optional arrays or fields (build the arrays "
                                    "with NumPy and make a new Packing instead)");
            p.add(to_vec3(position), radius, type);
          },
          py::arg("position"), py::arg("radius"), py::arg("type") = 0,
          "Appends one particle (invalidates the array views).")
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
              if (f.name == name) return view(f.values, self);
            throw py::key_error(fmt::format("field '{}': not in this packing", name));
          },
          py::arg("name"), "View of the extra scalar field `name` (KeyError if absent).")
      .def(
          "set_field",
          [](Packing& p, const std::string& name, py::object values) {
            auto v = from_numpy<double>(values, name.c_str(), static_cast<py::ssize_t>(p.size()));
            assign_in_place(p.field_or_add(name).values, std::move(v));
          },
          py::arg("name"), py::arg("values"), "Adds or replaces the extra scalar field `name` (one value per particle).")
      .def(
          "remove_field",
          [](Packing& p, const std::string& name) {
            std::erase_if(p.fields, [&](const ScalarField& f) { return f.name == name; });
          },
          py::arg("name"))
      .def("__repr__", [](const Packing& p) {
        return fmt::format("<packlab.Packing: {} particles, {} bonds, box {:g} x {:g} x {:g}>", p.size(),
                           p.bonds.size(), p.box.length.x, p.box.length.y, p.box.length.z);
      });
}

}  // namespace packlab::python
