// packlab._core: the compiled part of the Python package `packlab` (pybind11, NumPy).
// One file per concern, named after the part of src/packlab it binds (common.hpp lists them). Bad input raises
// packlab.InputError (a ValueError) with the message the command line prints.
#include "common.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/thread_wait.hpp"
#include "packlab/io/report.hpp"

PYBIND11_MODULE(_core, m) {
  packlab::fixed_thread_teams();  // the thread counts asked for, never fewer (core/thread_wait.hpp)
  m.doc() = "packlab: random sphere packings, their microstructure and DEM load tests (compiled core).";
  py::register_exception<packlab::InputError>(m, "InputError", PyExc_ValueError);
  m.attr("InputError").attr("__doc__") =
      "Bad input (a value out of range, a malformed file, an unknown name): the message is the one the "
      "command line prints after 'packlab: error:'. Derives from ValueError.";
  m.attr("__version__") = packlab::io::version();
  packlab::python::bind_packing(m);
  packlab::python::bind_io(m);
  packlab::python::bind_generate(m);
  packlab::python::bind_generate_vem(m);
  packlab::python::bind_generate_ls(m);
  packlab::python::bind_generate_shake(m);
  packlab::python::bind_generate_scrm(m);
  packlab::python::bind_analyze(m);
  packlab::python::bind_analyze_rdf(m);
  packlab::python::bind_analyze_pore_size(m);
  packlab::python::bind_analyze_fabric(m);
  packlab::python::bind_analyze_fits(m);
  packlab::python::bind_dem(m);
  packlab::python::bind_oscillatory_shear(m);
  packlab::python::bind_generate_fba(m);
  packlab::python::bind_generate_bd(m);
  packlab::python::bind_generate_opal(m);
  packlab::python::bind_uniaxial_compression(m);
}
