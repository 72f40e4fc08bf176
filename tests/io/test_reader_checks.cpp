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
#include "packlab/io/xml.hpp"

namespace packlab::io {
namespace {

namespace fs = std::filesystem;

class ReaderChecks : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) /
           fmt::format("packlab_reader_checks_{}_{}", info->name(), static_cast<long>(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path file(const std::string& name) const { return dir_ / name; }
  fs::path write_file(const std::string& name, const std::string& text) const {
    std::ofstream(file(name), std::ios::binary) << text;
    return file(name);
  }
  std::string read_text(const std::string& name) const {
    std::ifstream in(file(name), std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  fs::path dir_;
};

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
// Bonds

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

}  // namespace
}  // namespace packlab::io
