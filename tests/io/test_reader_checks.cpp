// What every reader refuses (one shared check, so all formats agree): non-finite numbers,
// particle counts that disagree with the rows, particles outside an open box, self-bonds and
// duplicate bonds; and what packlab writes always reads back. Also: XML with very many
// attributes parses in linear time.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "packlab/core/error.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/io/packing_io.hpp"
#include "io_test_dir.hpp"
#include "packlab/io/xml.hpp"

namespace packlab::io {
namespace {

namespace fs = std::filesystem;

class ReaderChecks : public IoTestDir {};

// One line, every part present.
void expect_input_error(const fs::path& path, std::initializer_list<std::string> parts) {
  try {
    (void)read_packing(path);
    ADD_FAILURE() << path << ": expected InputError, the file was read";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const auto& part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
  }
}

const std::string xyz_header = "Properties=species:S:1:pos:R:3:radius:R:1";
const std::string dump_head =
    "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp ff\n0 1\n0 1\n0 1\n"
    "ITEM: ATOMS id x y z radius\n";

// ---------------------------------------------------------------------------------------------
// Non-finite numbers

TEST_F(ReaderChecks, NonFiniteBoxIsRefusedInEveryFormat) {
  expect_input_error(write_file("a.xyz", "1\nLattice=\"1 0 0 0 1 0 0 0 1\" Origin=\"nan 0 0\" " + xyz_header +
                                             "\nT0 0.5 0.5 0.5 0.1\n"),
                     {"a.xyz:2:", "Origin entry = 'nan'", "finite"});
  expect_input_error(write_file("a.csv", "# box lo nan 0 0 length 1 1 1 periodic T T T\nx,y,z,r\n0.5,0.5,0.5,0.1\n"),
                     {"a.csv:1:", "box lo = 'nan'", "finite"});
  expect_input_error(write_file("a.txt", "# box 1 inf 1\n0.5 0.5 0.5 0.1\n"), {"a.txt:1:", "'inf'", "finite"});
  expect_input_error(write_file("a.data", "t\n\n1 atoms\n0 inf xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
                                          "1 1 0.2 1 0.5 0.5 0.5\n"),
                     {"a.data:4:", "'inf'", "finite"});
  expect_input_error(write_file("a.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n"
                                          "0 1\n0 inf\n0 1\nITEM: ATOMS x y z radius\n0.5 0.5 0.5 0.1\n"),
                     {"a.dump:7:", "'inf'", "finite"});
  // VTU: the box written by packlab, then its origin replaced by NaN.
  Packing packing;
  packing.box.length = {1, 1, 1};
  packing.add({0.5, 0.5, 0.5}, 0.1);
  write_packing(packing, file("ok.vtu"));
  std::string text = file_text("ok.vtu");
  const auto at = text.find('\n', text.find("Name=\"box_lo\"")) + 1;
  text.replace(text.find('0', at), 1, "nan");
  expect_input_error(write_file("a.vtu", text), {"a.vtu:", "'nan'", "box_lo", "finite"});
}

TEST_F(ReaderChecks, NonFiniteCoordinatesAndRadiiAreRefused) {
  expect_input_error(write_file("b.xyz", "2\n" + xyz_header + "\nT0 0 0 0 1\nT0 0 NaN 0 1\n"),
                     {"b.xyz:4:", "position coordinate = 'NaN'", "finite"});
  expect_input_error(write_file("b.csv", "x,y,z,r\n0,0,0,1\n0,0,0,inf\n"), {"b.csv:3:", "radius r = 'inf'"});
  expect_input_error(write_file("b.txt", "0 0 -inf 1\n"), {"b.txt:1:", "z = '-inf'"});
  expect_input_error(write_file("b.dump", dump_head + "1 .5 .5 .5 .1\n2 .5 nan .5 .1\n"),
                     {"b.dump:11:", "coordinate = 'nan'"});
  expect_input_error(write_file("b.xyz2.xyz", "1\n" + xyz_header + ":velo:R:3\nT0 0 0 0 1 0 inf 0\n"),
                     {"b.xyz2.xyz:3:", "velocity component = 'inf'"});
  // Extra fields may hold NaN (a missing value), and read back as NaN.
  const Packing with_nan_field =
      read_packing(write_file("f.xyz", "1\n" + xyz_header + ":score:R:1\nT0 0 0 0 1 nan\n"));
  ASSERT_EQ(with_nan_field.fields.size(), 1u);
  EXPECT_TRUE(std::isnan(with_nan_field.fields[0].values[0]));
}

TEST_F(ReaderChecks, ValidateRefusesNonFiniteBoxOriginAndVelocities) {
  Packing packing;
  packing.add({0, 0, 0}, 0.1);
  packing.box.lo.y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(packing.validate(), InputError);
  packing.box.lo.y = 0.0;
  packing.velocity.push_back({0.0, std::numeric_limits<double>::infinity(), 0.0});
  EXPECT_THROW(packing.validate(), InputError);
  packing.velocity.clear();
  packing.density.push_back(std::numeric_limits<double>::infinity());
  EXPECT_THROW(packing.validate(), InputError);
  packing.density.clear();
  EXPECT_NO_THROW(packing.validate());
  EXPECT_THROW(write_packing([&] {
                 Packing bad = packing;
                 bad.box.lo.x = std::numeric_limits<double>::infinity();
                 return bad;
               }(),
                            file("w.xyz")),
               InputError);
  EXPECT_FALSE(fs::exists(file("w.xyz")));
}

// ---------------------------------------------------------------------------------------------
// Counts

TEST_F(ReaderChecks, XyzCountMustMatchTheRows) {
  expect_input_error(write_file("small.xyz", "1\n" + xyz_header + "\nT0 0 0 0 1\nT0 3 0 0 1\n"),
                     {"small.xyz:4:", "line 1 announces 1 particles", "more lines"});
  expect_input_error(write_file("large.xyz", "3\n" + xyz_header + "\nT0 0 0 0 1\nT0 3 0 0 1\n"),
                     {"large.xyz", "3 particle lines", "found 2"});
  // A count that is too large, followed by the next frame of a trajectory.
  expect_input_error(
      write_file("large2.xyz", "3\n" + xyz_header + "\nT0 0 0 0 1\nT0 3 0 0 1\n2\n" + xyz_header + "\n"),
      {"large2.xyz:5:", "announces 3 particles, but only 2 particle lines"});
  // Trajectories: only the first frame is read; trailing blank lines are fine.
  const Packing first = read_packing(write_file(
      "trajectory.xyz", "2\n" + xyz_header + "\nT0 0 0 0 1\nT0 3 0 0 1\n1\n" + xyz_header + "\nT0 9 9 9 1\n\n"));
  EXPECT_EQ(first.size(), 2u);
  EXPECT_EQ(read_packing(write_file("blank.xyz", "1\n" + xyz_header + "\nT0 0 0 0 1\n\n\n")).size(), 1u);
}

TEST_F(ReaderChecks, DumpCountMustMatchTheRows) {
  expect_input_error(write_file("small.dump", dump_head + "1 .5 .5 .5 .1\n2 .5 .5 .5 .1\n3 .5 .5 .5 .1\n"),
                     {"small.dump:12:", "NUMBER OF ATOMS is 2, but more atom lines follow"});
  expect_input_error(write_file("large.dump", dump_head + "1 .5 .5 .5 .1\nITEM: TIMESTEP\n1\n"),
                     {"large.dump:11:", "NUMBER OF ATOMS is 2, but the frame has only 1 atom lines"});
  const Packing first =
      read_packing(write_file("two_frames.dump", dump_head + "1 .5 .5 .5 .1\n2 .5 .5 .5 .1\n" + dump_head +
                                                     "1 .5 .5 .5 .1\n2 .5 .5 .5 .1\n"));
  EXPECT_EQ(first.size(), 2u);
}

// ---------------------------------------------------------------------------------------------
// Particles outside an open box

TEST_F(ReaderChecks, ParticleFarOutsideAnOpenBoxIsRefusedWithItsLine) {
  const std::string lattice = "Lattice=\"10 0 0 0 10 0 0 0 10\" pbc=\"T T F\" ";
  expect_input_error(write_file("far.xyz", "2\n" + lattice + xyz_header + "\nT0 5 5 5 0.5\nT0 5 5 25 0.5\n"),
                     {"far.xyz:4:", "particle 1", "outside the open box along z", "z = 25", "radius 0.5",
                      "box [0, 10]", "at most its radius + 1e-09"});
  expect_input_error(write_file("far.csv", "# box lo 0 0 0 length 10 10 10 periodic F T T\nx,y,z,r\n-3,5,5,1\n"),
                     {"far.csv:3:", "along x", "x = -3"});
  expect_input_error(write_file("far.txt", "# box lo 0 0 0 length 10 10 10 periodic T F T\n5 11.6 5 0.5\n"),
                     {"far.txt:2:", "along y"});
  expect_input_error(write_file("far.data", "t pbc=T T F\n\n1 atoms\n0 10 xlo xhi\n0 10 ylo yhi\n0 10 zlo zhi\n\n"
                                            "Atoms\n\n1 1 1 1 5 5 -20\n"),
                     {"far.data:10:", "along z"});
  expect_input_error(write_file("far.dump", dump_head + "2 .5 .5 .5 .1\n1 .5 .5 7 .1\n"),
                     {"far.dump:11:", "particle 0", "along z"});
  // Up to one radius (+ the tolerance) outside is accepted: the sphere still touches the box.
  const double r = 0.5;
  const Packing touching = read_packing(write_file(
      "touching.xyz", fmt::format("2\n{}{}\nT0 5 5 {:.17g} {}\nT0 5 5 -0.5 {}\n", lattice, xyz_header,
                                  10.0 + r + 0.5e-9 * 10.0, r, r)));
  EXPECT_EQ(touching.size(), 2u);
  // Periodic axes are not checked: positions there are wrapped by whoever uses them.
  EXPECT_EQ(read_packing(write_file("periodic.xyz", "1\n" + lattice + xyz_header + "\nT0 25 -7 5 0.5\n")).size(),
            1u);
  // A box given by the caller must hold the particles too.
  ReadOptions options;
  options.box = Box{{0, 0, 0}, {1, 1, 1}, {false, false, false}};
  EXPECT_THROW((void)read_packing(write_file("given.txt", "5 5 5 0.5\n"), options), InputError);
}

TEST_F(ReaderChecks, WritersWidenAnOpenBoxThatParticlesLeftSoTheFileReadsBack) {
  // As a DEM run with an open z axis may leave it: one particle far above the box.
  Packing packing;
  packing.box = Box{{0, 0, 0}, {10, 10, 10}, {true, true, false}};
  packing.add({5, 5, 5}, 0.5);
  packing.add({5, 5, 30}, 0.5);
  packing.add({5, 5, -0.25}, 0.5);  // sticks out, within the tolerance: no widening on its account
  for (const char* name : {"w.xyz", "w.vtu", "w.data", "w.csv", "w.txt"}) {
    SCOPED_TRACE(name);
    write_packing(packing, file(name));
    const Packing back = read_packing(file(name));
    EXPECT_EQ(back.position, packing.position);
    EXPECT_EQ(back.box.periodic, packing.box.periodic);
    EXPECT_EQ(back.box.lo.x, 0.0);
    EXPECT_EQ(back.box.length.x, 10.0);  // periodic axes untouched
    EXPECT_EQ(back.box.lo.z, -0.75);     // the spheres' extent along the open axis
    EXPECT_EQ(back.box.lo.z + back.box.length.z, 30.5);
  }
  // Inside the box, the box is written unchanged.
  packing.position[1].z = 9.0;
  write_packing(packing, file("inside.xyz"));
  EXPECT_EQ(read_packing(file("inside.xyz")).box.length.z, 10.0);
}

// ---------------------------------------------------------------------------------------------
// Bonds

std::string vtu_with_bonds(const std::string& connectivity, std::size_t bonds, const std::string& images) {
  std::string cell_values, rest, offsets = "1 2 3", types = "1 1 1";
  for (std::size_t b = 0; b < bonds; ++b) {
    cell_values += " 0";
    rest += " 1";
    offsets += fmt::format(" {}", 3 + 2 * (b + 1));
    types += " 3";
  }
  return fmt::format(
      R"(<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0">
 <UnstructuredGrid>
  <FieldData>
   <DataArray type="Float64" Name="box_lo" format="ascii">0 0 0</DataArray>
   <DataArray type="Float64" Name="box_length" format="ascii">10 10 10</DataArray>
   <DataArray type="Int32" Name="periodic" format="ascii">1 1 1</DataArray>
  </FieldData>
  <Piece NumberOfPoints="3" NumberOfCells="{0}">
   <PointData><DataArray type="Float64" Name="radius" format="ascii">0.5 0.5 0.5</DataArray></PointData>
   <CellData>
    <DataArray type="Int32" Name="bond_material" format="ascii">-1 -1 -1{1}</DataArray>
    <DataArray type="Int32" Name="bond_state" format="ascii">-1 -1 -1{1}</DataArray>
    <DataArray type="Float64" Name="bond_rest_length" format="ascii">-1 -1 -1{2}</DataArray>
    <DataArray type="Int32" Name="bond_image" NumberOfComponents="3" format="ascii">0 0 0 0 0 0 0 0 0 {3}</DataArray>
   </CellData>
   <Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">1 1 1 2 1 1 3 1 1</DataArray></Points>
   <Cells>
    <DataArray type="Int64" Name="connectivity" format="ascii">0 1 2 {4}</DataArray>
    <DataArray type="Int64" Name="offsets" format="ascii">{5}</DataArray>
    <DataArray type="UInt8" Name="types" format="ascii">{6}</DataArray>
   </Cells>
  </Piece>
 </UnstructuredGrid>
</VTKFile>
)",
      3 + bonds, cell_values, rest, images, connectivity, offsets, types);
}

TEST_F(ReaderChecks, SelfBondsAndDuplicateBondsAreRefused) {
  EXPECT_EQ(read_packing(write_file("ok.vtu", vtu_with_bonds("0 1 1 2", 2, "0 0 0 0 0 0"))).bonds.size(), 2u);
  expect_input_error(write_file("self.vtu", vtu_with_bonds("0 1 1 1", 2, "0 0 0 0 0 0")),
                     {"self.vtu", "bond 1 joins particle 1 to itself"});
  expect_input_error(write_file("twice.vtu", vtu_with_bonds("0 1 0 1", 2, "0 0 0 0 0 0")),
                     {"twice.vtu", "bonds 0 and 1 both join particles 0 and 1", "at most once"});
  // j -> i with the opposite image is the same bond as i -> j.
  expect_input_error(write_file("reversed.vtu", vtu_with_bonds("0 1 1 0", 2, "1 0 0 -1 0 0")),
                     {"reversed.vtu", "bonds 0 and 1"});
  // Different images are different bonds; a bond to one's own periodic image is a real bond.
  const Packing images = read_packing(write_file("images.vtu", vtu_with_bonds("0 1 0 1 2 2", 3, "0 0 0 1 0 0 0 1 0")));
  EXPECT_EQ(images.bonds.size(), 3u);
  expect_input_error(write_file("self_images.vtu", vtu_with_bonds("2 2 2 2", 2, "0 1 0 0 -1 0")),
                     {"self_images.vtu", "bonds 0 and 1"});
}

TEST_F(ReaderChecks, WritersRefuseSelfAndDuplicateBonds) {
  Packing packing;
  packing.box.length = {10, 10, 10};
  packing.add({1, 1, 1}, 0.5);
  packing.add({2, 1, 1}, 0.5);
  packing.bonds.add(0, 1, {0, 0, 0}, 0, 1.0);
  packing.bonds.add(1, 0, {0, 0, 0}, 0, 1.0);
  EXPECT_THROW(write_packing(packing, file("dup.vtu")), InputError);
  packing.bonds = {};
  packing.bonds.add(0, 0, {0, 0, 0}, 0, 0.0);
  EXPECT_THROW(write_packing(packing, file("self.vtu")), InputError);
  EXPECT_FALSE(fs::exists(file("dup.vtu")) || fs::exists(file("self.vtu")));
}

// ---------------------------------------------------------------------------------------------
// XML

TEST_F(ReaderChecks, XmlElementWithManyAttributesParses) {
  // Checking each attribute against all earlier ones made this quadratic (~10 s for 1e5).
  constexpr int count = 100000;
  std::string text = "<root";
  text.reserve(static_cast<std::size_t>(count) * 16);
  for (int k = 0; k < count; ++k) text += fmt::format(" a{}=\"{}\"", k, k);
  text += "/>";
  const detail::XmlDocument doc(text, "many.xml");
  ASSERT_EQ(doc.root().attributes.size(), static_cast<std::size_t>(count));
  EXPECT_EQ(doc.root().attributes.back().second, "99999");
  // A repeated attribute, the last of them, is still found.
  text.insert(text.size() - 2, " a7=\"x\"");
  EXPECT_THROW(detail::XmlDocument(text, "repeated.xml"), InputError);
}

TEST_F(ReaderChecks, VtuWithManyAttributesAndArraysIsReadOrRefusedQuickly) {
  // A DataArray element carrying 1e5 extra attributes, and a second DataArray named like the
  // first among thousands: both linear.
  Packing packing;
  packing.box.length = {1, 1, 1};
  packing.add({0.5, 0.5, 0.5}, 0.1);
  write_packing(packing, file("base.vtu"));
  std::string text = file_text("base.vtu");
  std::string attributes;
  for (int k = 0; k < 100000; ++k) attributes += fmt::format(" x{}=\"1\"", k);
  text.insert(text.find("Name=\"radius\"") - 1, attributes);
  EXPECT_EQ(read_packing(write_file("attributes.vtu", text)).size(), 1u);
}

}  // namespace
}  // namespace packlab::io
