// packlab.read / packlab.write: the same files as the command line, chosen by extension
// (.xyz .extxyz .vtu .data .lmp .dump .lammpstrj .csv .txt .dat, LAMMPS data.* / dump.*).
#include "common.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::python {

void bind_io(py::module_& m) {
  m.def(
      "read",
      [](const std::filesystem::path& path, std::optional<Box> box) {
        io::ReadOptions options;
        options.box = box;
        py::gil_scoped_release nogil;
        return io::read_packing(path, options);
      },
      py::arg("path"), py::arg("box") = py::none(), R"doc(
Reads a packing; the format follows the extension, as on the command line (`packlab convert`):
.xyz/.extxyz (extended XYZ, OVITO), .vtu (ParaView, with bonds), .data/.lmp/data.* (LAMMPS
data, atom_style sphere), .dump/.lammpstrj/dump.* (LAMMPS dump, first frame), .csv, .txt/.dat
(x y z r, PackingGeneration). box: a Box for files that carry none (or to override the file's);
without it such files get the bounding box of the spheres, open on every axis.
Raises InputError naming the file, the line and what was expected.
)doc");
  m.def(
      "write",
      [](const Packing& packing, const std::filesystem::path& path, const std::string& comment) {
        io::WriteOptions options;
        options.comment = comment;
        py::gil_scoped_release nogil;
        io::write_packing(packing, path, options);
      },
      py::arg("packing"), py::arg("path"), py::arg("comment") = "", R"doc(
Writes a packing atomically (temporary name, then rename) with 17 significant digits, in the
format of the extension (see read; dumps are read-only). comment: provenance text stored in
the file header where the format has a place for it.
)doc");
  m.def(
      "format_of", [](const std::filesystem::path& path) { return io::format_name(io::format_from_path(path)); },
      py::arg("path"), "Name of the format packlab uses for this path (InputError for an unknown extension).");
  m.def(
      "bounding_box", &io::bounding_box, py::arg("packing"),
      "Bounding box of the spheres (centre +- radius), open on every axis.");
}

}  // namespace packlab::python
