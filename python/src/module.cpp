// packlab._core: the compiled part of the Python package `packlab` (pybind11, NumPy).
// One file per concern: packing.cpp (Packing, Box, Bonds), io.cpp (read/write), generate.cpp
// (generators), analyze.cpp (analyses), dem.cpp (engine, relax). Bad input raises
// packlab.InputError (a ValueError) with the message the command line prints.
#include "common.hpp"
#include "packlab/core/error.hpp"
#include "packlab/io/report.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() = "packlab: random sphere packings, their microstructure and DEM load tests (compiled core).";
  py::register_exception<packlab::InputError>(m, "InputError", PyExc_ValueError);
  m.attr("InputError").attr("__doc__") =
      "Bad input (a value out of range, a malformed file, an unknown name): the message is the one the "
      "command line prints after 'packlab: error:'. Derives from ValueError.";
  m.attr("__version__") = packlab::io::version();
  packlab::python::bind_packing(m);
  packlab::python::bind_io(m);
  packlab::python::bind_generate(m);
  packlab::python::bind_analyze(m);
  packlab::python::bind_dem(m);
  packlab::python::bind_shear(m);
  packlab::python::bind_opal(m);
  packlab::python::bind_compress(m);
}
