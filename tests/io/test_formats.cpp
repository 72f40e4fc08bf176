// File formats: bit-exact round trips, files written by other programs (PackingGeneration,
// LAMMPS, OVITO-style extended XYZ, the ../shared/peers/dem awk generator) and error paths.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <typeinfo>

#include "packlab/core/error.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/io/packing_io.hpp"
#include "io_test_dir.hpp"

namespace packlab::io {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards.
class FormatsTest : public IoTestDir {
 protected:
  // Writes `original` to `name` (the format from the extension) and reads it back.
  Packing round_trip(const Packing& original, const std::string& name, const WriteOptions& options = {}) const {
    write_packing(original, file(name), options);
    return read_packing(file(name));
  }
};

// Every optional field filled, full-precision doubles, several types, bonds with images.
Packing random_packing(std::uint64_t seed, std::size_t n = 40) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  Packing packing;
  packing.box.lo = {-1.25, 0.5, 3.0};
  packing.box.length = {7.0 + unit(rng), 8.0 + unit(rng), 9.0 + unit(rng)};
  packing.box.periodic = {true, false, true};
  for (std::size_t k = 0; k < n; ++k) {
    Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = packing.box.lo[a] + unit(rng) * packing.box.length[a];
    packing.add(p, 0.1 + 0.4 * unit(rng), static_cast<int>(rng() % 5));
    packing.velocity.push_back({normal(rng), normal(rng), normal(rng)});
    packing.angular_velocity.push_back({1e3 * normal(rng), normal(rng), -normal(rng)});
    packing.density.push_back(1000.0 + 4000.0 * unit(rng));
    packing.fixed.push_back(rng() % 2 ? 1 : 0);
  }
  auto& stress = packing.field_or_add("stress");
  for (auto& value : stress.values) value = 1e6 * normal(rng);
  auto& coordination = packing.field_or_add("coordination");
  for (auto& value : coordination.values) value = static_cast<double>(rng() % 12);
  for (int b = 0; b < 25; ++b) {
    const int i = static_cast<int>(rng() % n);
    const int j = static_cast<int>((static_cast<std::size_t>(i) + 1 + rng() % (n - 1)) % n);
    const std::array<int, 3> image{static_cast<int>(rng() % 3) - 1, 0, static_cast<int>(rng() % 3) - 1};
    const int material = static_cast<int>(rng() % 3);
    const double rest_length = 0.2 + unit(rng);
    const int state = static_cast<int>(rng() % 2);
    // A pair is bonded once (i, j, s and j, i, -s are the same bond): skip repeats.
    bool repeated = false;
    for (std::size_t c = 0; c < packing.bonds.size(); ++c) {
      const auto& s = packing.bonds.image[c];
      repeated |= (packing.bonds.i[c] == i && packing.bonds.j[c] == j && s == image) ||
                  (packing.bonds.i[c] == j && packing.bonds.j[c] == i &&
                   s == std::array<int, 3>{-image[0], -image[1], -image[2]});
    }
    if (!repeated) packing.bonds.add(i, j, image, material, rest_length, state);
  }
  packing.validate();
  return packing;
}

void expect_same_box(const Box& expected, const Box& actual) {
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(expected.lo[a], actual.lo[a]) << "axis " << a;
    EXPECT_EQ(expected.length[a], actual.length[a]) << "axis " << a;
    EXPECT_EQ(expected.periodic[static_cast<std::size_t>(a)], actual.periodic[static_cast<std::size_t>(a)])
        << "axis " << a;
  }
}

void expect_same_geometry(const Packing& expected, const Packing& actual) {
  expect_same_box(expected.box, actual.box);
  ASSERT_EQ(expected.size(), actual.size());
  EXPECT_EQ(expected.position, actual.position);
  EXPECT_EQ(expected.radius, actual.radius);
  EXPECT_EQ(expected.type, actual.type);
}

void expect_same_fields(const Packing& expected, const Packing& actual);

// Geometry, velocities, angular velocities, densities, fixed flags and fields: every
// per-particle value (what xyz and vtu keep).
void expect_same_particles(const Packing& expected, const Packing& actual) {
  expect_same_geometry(expected, actual);
  EXPECT_EQ(expected.velocity, actual.velocity);
  EXPECT_EQ(expected.angular_velocity, actual.angular_velocity);
  EXPECT_EQ(expected.density, actual.density);
  EXPECT_EQ(expected.fixed, actual.fixed);
  expect_same_fields(expected, actual);
}

void expect_same_fields(const Packing& expected, const Packing& actual) {
  ASSERT_EQ(expected.fields.size(), actual.fields.size());
  for (std::size_t f = 0; f < expected.fields.size(); ++f) {
    EXPECT_EQ(expected.fields[f].name, actual.fields[f].name);
    EXPECT_EQ(expected.fields[f].values, actual.fields[f].values) << expected.fields[f].name;
  }
}

void expect_same_bonds(const Bonds& expected, const Bonds& actual) {
  EXPECT_EQ(expected.i, actual.i);
  EXPECT_EQ(expected.j, actual.j);
  EXPECT_EQ(expected.image, actual.image);
  EXPECT_EQ(expected.material, actual.material);
  EXPECT_EQ(expected.rest_length, actual.rest_length);
  EXPECT_EQ(expected.state, actual.state);
}

// Expects InputError whose message contains every one of `parts` (file name, line, ...).
template <typename Action>
void expect_input_error(Action&& action, std::initializer_list<std::string> parts) {
  try {
    action();
    ADD_FAILURE() << "expected InputError, nothing was thrown";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const auto& part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
  }
}

// ---------------------------------------------------------------------------------------------
// Extensions

TEST(FormatFromPath, KnowsEveryExtensionAndLammpsPrefixes) {
  const std::pair<const char*, Format> cases[] = {
      {"a.xyz", Format::xyz},          {"a.extxyz", Format::xyz},         {"dir/a.VTU", Format::vtu},
      {"a.data", Format::lammps_data}, {"a.lmp", Format::lammps_data},    {"a.dump", Format::lammps_dump},
      {"a.lammpstrj", Format::lammps_dump}, {"a.csv", Format::csv},      {"a.txt", Format::text},
      {"a.dat", Format::text},         {"data.packing", Format::lammps_data}, {"dump.relax", Format::lammps_dump}};
  for (const auto& [path, format] : cases) EXPECT_EQ(format_from_path(path), format) << path;
  EXPECT_EQ(format_name(Format::lammps_data), "lammps-data");
}

TEST(FormatFromPath, UnknownExtensionIsInputError) {
  expect_input_error([] { format_from_path("packing.pdb"); }, {"packing.pdb", ".pdb", ".xyz"});
  expect_input_error([] { read_packing("no_extension"); }, {"no_extension"});
  expect_input_error([] { write_packing(random_packing(1), "out.h5"); }, {"out.h5"});
}

// ---------------------------------------------------------------------------------------------
// Round trips (bitwise)

TEST_F(FormatsTest, XyzRoundTripKeepsEveryPerParticleField) {
  const Packing original = random_packing(11);
  const Packing back = round_trip(original, "p.xyz", {.comment = "packlab test \"quoted\" seed=11"});
  expect_same_particles(original, back);
  EXPECT_TRUE(back.bonds.empty());
}

TEST_F(FormatsTest, XyzHeaderIsWhatOvitoExpects) {
  Packing packing;
  packing.box.length = {2.0, 3.0, 4.0};
  packing.box.periodic = {true, true, false};
  packing.add({0.5, 0.5, 0.5}, 0.25, 3);
  write_xyz(packing, file("p.xyz"), {});
  std::ifstream in(file("p.xyz"));
  std::string count, header, row;
  std::getline(in, count);
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_EQ(count, "1");
  EXPECT_EQ(header,
            "Lattice=\"2 0 0 0 3 0 0 0 4\" Origin=\"0 0 0\" pbc=\"T T F\" "
            "Properties=species:S:1:pos:R:3:radius:R:1");
  EXPECT_EQ(row, "T3 0.5 0.5 0.5 0.25");
}

TEST_F(FormatsTest, VtuRoundTripKeepsEverythingIncludingBonds) {
  const Packing original = random_packing(12);
  const Packing back = round_trip(original, "p.vtu", {.comment = "a -- comment with <xml> & dashes-"});
  expect_same_particles(original, back);
  expect_same_bonds(original.bonds, back.bonds);
}

TEST_F(FormatsTest, VtuRoundTripWithoutOptionalFieldsOrBonds) {
  Packing original;
  original.box.length = {5.0, 5.0, 5.0};
  original.add({1.0, 2.0, 3.0}, 0.5, 0);
  original.add({2.0, 2.0, 3.0}, 0.5, 1);
  original.field_or_add("a & b <c>").values = {1.5, -2.5};  // names are XML-escaped
  write_vtu(original, file("p.vtu"), {});
  const Packing back = read_vtu(file("p.vtu"), {});
  expect_same_geometry(original, back);
  EXPECT_TRUE(back.velocity.empty());
  EXPECT_TRUE(back.angular_velocity.empty());
  EXPECT_TRUE(back.density.empty());
  EXPECT_TRUE(back.fixed.empty());
  EXPECT_TRUE(back.bonds.empty());
  expect_same_fields(original, back);
}

TEST_F(FormatsTest, LammpsDataRoundTripKeepsTypeRadiusDensityAndVelocities) {
  const Packing original = random_packing(13);
  write_packing(original, file("p.data"),
                {.comment = "relaxed packing pbc=F F F (must not confuse the reader)"});
  const Packing back = read_packing(file("p.data"));
  expect_same_geometry(original, back);
  EXPECT_EQ(original.density, back.density);
  EXPECT_EQ(original.velocity, back.velocity);
  EXPECT_EQ(original.angular_velocity, back.angular_velocity);
  EXPECT_TRUE(back.fixed.empty());
  EXPECT_TRUE(back.fields.empty());
  EXPECT_TRUE(back.bonds.empty());
}

TEST_F(FormatsTest, LammpsDataWithoutDensityWritesOne) {
  Packing original;
  original.box.length = {4.0, 4.0, 4.0};
  original.add({1.0, 1.0, 1.0}, 0.5, 0);
  write_lammps_data(original, file("p.lmp"), {});
  const Packing back = read_lammps_data(file("p.lmp"), {});
  expect_same_geometry(original, back);
  EXPECT_EQ(back.density, std::vector<double>{1.0});
  EXPECT_TRUE(back.velocity.empty());
}

TEST_F(FormatsTest, CsvRoundTripKeepsPositionsRadiiAndTypes) {
  const Packing original = random_packing(14);
  const Packing back = round_trip(original, "p.csv", {.comment = "box is not the box line"});
  expect_same_geometry(original, back);
  EXPECT_TRUE(back.velocity.empty());
  EXPECT_TRUE(back.fields.empty());
}

TEST_F(FormatsTest, TextRoundTripKeepsPositionsRadiiAndTypes) {
  const Packing original = random_packing(15);
  const Packing back = round_trip(original, "p.txt", {.comment = "box 1 2 3 is not the box line"});
  expect_same_geometry(original, back);
  EXPECT_TRUE(back.velocity.empty());
}

TEST_F(FormatsTest, TextWithDefaultBoxAndTypeZeroIsAnchorFormat) {
  Packing packing;
  packing.box.length = {3.0, 3.0, 3.0};
  packing.add({0.1, 0.2, 0.3}, 0.5, 0);
  write_text(packing, file("p.txt"), {});
  std::ifstream in(file("p.txt"));
  std::string first, second;
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_EQ(first, "# box 3 3 3");
  EXPECT_EQ(second, "0.10000000000000001 0.20000000000000001 0.29999999999999999 0.5");
  expect_same_geometry(packing, read_text(file("p.txt"), {}));
}

TEST_F(FormatsTest, MixedPeriodicityAndOffsetOriginSurviveEveryFormat) {
  for (const std::array<bool, 3> periodic :
       {std::array<bool, 3>{true, true, true}, std::array<bool, 3>{false, false, false},
        std::array<bool, 3>{false, true, false}, std::array<bool, 3>{true, true, false}}) {
    Packing original = random_packing(16, 10);
    original.box.periodic = periodic;
    for (const char* name : {"m.xyz", "m.vtu", "m.data", "m.csv", "m.txt"}) {
      SCOPED_TRACE(name);
      write_packing(original, file(name));
      expect_same_geometry(original, read_packing(file(name)));
    }
  }
}

TEST_F(FormatsTest, ExtremeDoublesRoundTripExactly) {
  Packing original;
  original.box.lo = {-0.0, -1e-300, 1e300};
  original.box.length = {1e-5, 1e5, 0.1};
  const double tiny = std::numeric_limits<double>::denorm_min();
  original.add({0.1, 1.0 / 3.0, -2.0 / 3.0}, std::numeric_limits<double>::min(), 0);
  original.add({tiny, -tiny, 5e-320}, 1e200, 2);
  original.add({std::nextafter(1.0, 2.0), -std::nextafter(1.0, 0.0), 1e300}, 0.1, 1);
  original.velocity = {{tiny, 0.0, -0.0}, {1e-310, 1.0, 2.0}, {3.0, 4.0, 5.0}};
  for (const char* name : {"e.xyz", "e.vtu", "e.data", "e.csv", "e.txt"}) {
    SCOPED_TRACE(name);
    write_packing(original, file(name));
    const Packing back = read_packing(file(name));
    expect_same_geometry(original, back);
    if (format_from_path(name) == Format::xyz || format_from_path(name) == Format::vtu) {
      EXPECT_EQ(original.velocity, back.velocity);
    }
  }
}

TEST_F(FormatsTest, BoxWhoseUpperBoundRoundsSurvivesLammpsData) {
  Packing original;
  original.box.lo = {0.1, -0.7, 1.0 / 3.0};
  original.box.length = {1.0 / 3.0, 0.1 + 0.2, 2.0 / 3.0};
  ASSERT_NE((original.box.lo.x + original.box.length.x) - original.box.lo.x, original.box.length.x);
  original.add({0.2, -0.5, 0.5}, 0.05, 0);
  write_lammps_data(original, file("b.data"), {});
  expect_same_geometry(original, read_lammps_data(file("b.data"), {}));
}

TEST_F(FormatsTest, EmptyPackingWithBoxRoundTrips) {
  Packing original;
  original.box.length = {2.0, 3.0, 4.0};
  for (const char* name : {"z.xyz", "z.vtu", "z.data", "z.csv", "z.txt"}) {
    SCOPED_TRACE(name);
    write_packing(original, file(name));
    const Packing back = read_packing(file(name));
    EXPECT_EQ(back.size(), 0u);
    expect_same_box(original.box, back.box);
  }
}

TEST_F(FormatsTest, ReadOptionsBoxOverridesTheFileBox) {
  const Packing original = random_packing(17, 5);
  Box other;
  other.lo = {-10.0, -10.0, -10.0};
  other.length = {30.0, 30.0, 30.0};
  other.periodic = {false, true, false};
  for (const char* name : {"o.xyz", "o.vtu", "o.data", "o.csv", "o.txt"}) {
    SCOPED_TRACE(name);
    write_packing(original, file(name));
    expect_same_box(other, read_packing(file(name), {.box = other}).box);
  }
}

// ---------------------------------------------------------------------------------------------
// Files from other programs

// tests/data/anchor-packings.tar.xz, unpacked into the build folder by CMake.
fs::path anchor_packing_dir() { return PACKLAB_ANCHOR_PACKINGS; }

TEST(AnchorPackings, ReadWithBoxAndVolumeFractionFromTheReadme) {
  const fs::path dir = anchor_packing_dir();
  struct Expected {
    const char* file;
    double phi;  // README table, 6 digits
  };
  for (const Expected& expected :
       {Expected{"pg-ls-mono-10k.txt", 0.638255}, Expected{"pg-fba-mono-10k.txt", 0.634766},
        Expected{"pg-ls-bi-10k.txt", 0.722547}}) {
    SCOPED_TRACE(expected.file);
    const Packing packing = read_packing(dir / expected.file);
    ASSERT_EQ(packing.size(), 10000u);
    EXPECT_EQ(packing.box.lo, (Vec3{0.0, 0.0, 0.0}));
    EXPECT_EQ(packing.box.periodic, (std::array<bool, 3>{true, true, true}));
    EXPECT_EQ(packing.box.length.x, packing.box.length.y);
    EXPECT_EQ(packing.box.length.x, packing.box.length.z);
    EXPECT_NEAR(packing.volume_fraction(), expected.phi, 1e-5 * expected.phi);
    EXPECT_TRUE(std::all_of(packing.type.begin(), packing.type.end(), [](int t) { return t == 0; }));
    for (const Vec3& p : packing.position)
      for (int a = 0; a < 3; ++a) ASSERT_TRUE(p[a] >= 0.0 && p[a] < packing.box.length[a]);
  }
  const Packing bidisperse = read_packing(dir / "pg-ls-bi-10k.txt");
  const double large = *std::max_element(bidisperse.radius.begin(), bidisperse.radius.end());
  EXPECT_EQ(std::count(bidisperse.radius.begin(), bidisperse.radius.end(), large), 843);
}

TEST_F(FormatsTest, AnchorPackingSurvivesEveryFormat) {
  const fs::path dir = anchor_packing_dir();
  const Packing original = read_packing(dir / "pg-ls-bi-10k.txt");
  for (const char* name : {"a.xyz", "a.vtu", "a.data", "a.csv", "a.txt"}) {
    SCOPED_TRACE(name);
    write_packing(original, file(name));
    expect_same_geometry(original, read_packing(file(name)));
  }
}

TEST_F(FormatsTest, ReadsCommonShAwkDataFile) {
  // As written by write_data() in ../shared/peers/dem/common.sh.
  const auto path =
      write_file("data.relax",
                 "random spheres, Park-Miller seed 12345\n\n3 atoms\n1 atom types\n\n"
                 "0 2.3199999999999998e-06 xlo xhi\n0 2.3199999999999998e-06 ylo yhi\n"
                 "0 2.3199999999999998e-06 zlo zhi\n\nAtoms\n\n"
                 "1 1 4.9999999999999998e-07 3690 1.7336103396830713e-08 6.3375546155937387e-07 1.2e-06\n"
                 "2 1 4.9999999999999998e-07 3690 2.1e-06 1.1e-06 2.2e-07\n"
                 "3 1 4.9999999999999998e-07 3690 1e-06 2e-06 5e-07\n");
  const Packing packing = read_packing(path);
  ASSERT_EQ(packing.size(), 3u);
  EXPECT_EQ(packing.box.length,
            (Vec3{2.3199999999999998e-06, 2.3199999999999998e-06, 2.3199999999999998e-06}));
  EXPECT_EQ(packing.box.periodic, (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(packing.radius[0], 0.5 * 4.9999999999999998e-07);
  EXPECT_EQ(packing.density, (std::vector<double>{3690, 3690, 3690}));
  EXPECT_EQ(packing.type, (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(packing.position[0].x, 1.7336103396830713e-08);
}

TEST_F(FormatsTest, ReadsLammpsWriteDataOutput) {
  // LAMMPS's own write_data: style comment, image flags, atoms in processor order, velocities.
  const auto path =
      write_file("lammps.data",
                 "LAMMPS data file via write_data, version 2 Aug 2023, timestep = 1000, units = si\n\n"
                 "3 atoms\n2 atom types\n\n"
                 "-1.0 1.0 xlo xhi\n-2.0 2.0 ylo yhi\n0.0 5.0 zlo zhi\n0 0 0 xy xz yz\n\n"
                 "Atoms # sphere\n\n"
                 "3 2 0.5 2500 0.3 0.3 0.3 0 1 0\n"
                 "1 1 1.0 2000 0.1 0.1 0.1 0 0 0\r\n"
                 "2 1 1.0 2000 0.2 0.2 0.2 -1 0 0\n\n"
                 "Velocities\n\n"
                 "2 0.2 0 0 0 0 2\n1 0.1 0 0 0 0 1\n3 0.3 0 0 0 0 3\n");
  const Packing packing = read_packing(path);
  ASSERT_EQ(packing.size(), 3u);
  EXPECT_EQ(packing.position[0], (Vec3{0.1, 0.1, 0.1}));
  EXPECT_EQ(packing.position[2], (Vec3{0.3, 0.3, 0.3}));
  EXPECT_EQ(packing.type, (std::vector<int>{0, 0, 1}));
  EXPECT_EQ(packing.radius, (std::vector<double>{0.5, 0.5, 0.25}));
  EXPECT_EQ(packing.density, (std::vector<double>{2000, 2000, 2500}));
  EXPECT_EQ(packing.velocity[1], (Vec3{0.2, 0.0, 0.0}));
  EXPECT_EQ(packing.angular_velocity[2], (Vec3{0.0, 0.0, 3.0}));
  EXPECT_EQ(packing.box.lo, (Vec3{-1.0, -2.0, 0.0}));
  EXPECT_EQ(packing.box.length, (Vec3{2.0, 4.0, 5.0}));
}

TEST_F(FormatsTest, LammpsDataRejectsOtherAtomStylesAndTriclinicBoxes) {
  const std::string head = "title\n\n1 atoms\n1 atom types\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n";
  expect_input_error(
      [&] { read_packing(write_file("a.data", head + "\nAtoms # atomic\n\n1 1 0.5 0.5 0.5\n")); },
      {"a.data:9:", "atomic"});
  expect_input_error(
      [&] { read_packing(write_file("t.data", head + "0.5 0 0 xy xz yz\n\nAtoms\n\n1 1 1 1 .5 .5 .5\n")); },
      {"t.data:8:", "triclinic"});
  expect_input_error([&] { read_packing(write_file("c.data", head + "\nAtoms\n\n1 1 1 1 .5 .5\n")); },
                     {"c.data:11:", "id type diameter density x y z"});
  expect_input_error(
      [&] { read_packing(write_file("d.data", head + "\nAtoms\n\n1 1 1 1 .5 .5 .5\n1 1 1 1 .5 .5 .5\n")); },
      {"d.data:12:", "more than the 1 atoms"});
  expect_input_error([&] { read_packing(write_file("y.data", head + "\nAtoms\n\n1 2 1 1 .5 .5 .5\n")); },
                     {"y.data:11:", "atom type 2"});
}

TEST_F(FormatsTest, LammpsDumpWithShuffledColumnsAndIds) {
  const auto path = write_file("relax.lammpstrj",
                               "ITEM: TIMESTEP\n500\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS pp ff pp\n"
                               "0 10\n-5 5\n0 4\n"
                               "ITEM: ATOMS radius c_coord z type vx id x y vz vy\n"
                               "0.25 4 3.0 2 0.3 3 3.5 -3 0 0\n"
                               "0.5 6 1.0 1 0.1 1 1.5 -1 0 0\n"
                               "0.5 5 2.0 1 0.2 2 2.5 -2 0 0\n"
                               "ITEM: TIMESTEP\n600\nITEM: NUMBER OF ATOMS\n1\n");  // second frame ignored
  const Packing packing = read_packing(path);
  ASSERT_EQ(packing.size(), 3u);
  EXPECT_EQ(packing.position, (std::vector<Vec3>{{1.5, -1, 1.0}, {2.5, -2, 2.0}, {3.5, -3, 3.0}}));
  EXPECT_EQ(packing.radius, (std::vector<double>{0.5, 0.5, 0.25}));
  EXPECT_EQ(packing.type, (std::vector<int>{0, 0, 1}));
  EXPECT_EQ(packing.velocity[2], (Vec3{0.3, 0.0, 0.0}));
  EXPECT_TRUE(packing.angular_velocity.empty());
  ASSERT_NE(packing.field("c_coord"), nullptr);
  EXPECT_EQ(packing.field("c_coord")->values, (std::vector<double>{6, 5, 4}));
  EXPECT_EQ(packing.box.periodic, (std::array<bool, 3>{true, false, true}));
  EXPECT_EQ(packing.box.lo, (Vec3{0, -5, 0}));
  EXPECT_EQ(packing.box.length, (Vec3{10, 10, 4}));
}

TEST_F(FormatsTest, LammpsDumpWithScaledCoordinatesDiameterAndTriclinicHeader) {
  const auto path = write_file("dump.scaled",
                               "ITEM: TIMESTEP\n0\nITEM: UNITS\nsi\nITEM: NUMBER OF ATOMS\n2\n"
                               "ITEM: BOX BOUNDS xy xz yz fm pp ss\n2 6 0\n0 8 0.0\n0 2 0\n"
                               "ITEM: ATOMS id xs ys zs diameter omegax omegay omegaz\n"
                               "7 0.5 0.25 1 1.0 1 2 3\n4 0 0 0 0.5 4 5 6\n");
  const Packing packing = read_packing(path);
  ASSERT_EQ(packing.size(), 2u);
  EXPECT_EQ(packing.position, (std::vector<Vec3>{{2, 0, 0}, {4, 2, 2}}));
  EXPECT_EQ(packing.radius, (std::vector<double>{0.25, 0.5}));
  EXPECT_EQ(packing.angular_velocity[0], (Vec3{4, 5, 6}));
  EXPECT_EQ(packing.box.periodic, (std::array<bool, 3>{false, true, false}));
}

TEST_F(FormatsTest, LammpsDumpPrefersWrappedCoordinatesAndKeepsPartialTriplesAsFields) {
  const auto path =
      write_file("p.dump",
                 "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n0 2\n0 2\n0 2\n"
                 "ITEM: ATOMS xs radius id z x ys y omegaz vx diameter\n0.9 0.5 1 1.5 0.25 0.9 0.75 7 8 3\n");
  const Packing packing = read_packing(path);
  EXPECT_EQ(packing.position, (std::vector<Vec3>{{0.25, 0.75, 1.5}}));
  EXPECT_EQ(packing.radius, (std::vector<double>{0.5}));
  EXPECT_TRUE(packing.velocity.empty());
  EXPECT_TRUE(packing.angular_velocity.empty());
  ASSERT_NE(packing.field("omegaz"), nullptr);
  EXPECT_EQ(packing.field("omegaz")->values, (std::vector<double>{7}));
  EXPECT_EQ(packing.field("vx")->values, (std::vector<double>{8}));
}

TEST_F(FormatsTest, LammpsDumpErrors) {
  const std::string head =
      "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\n";
  expect_input_error(
      [&] { read_packing(write_file("a.dump", head + "ITEM: ATOMS id x y z\n1 .5 .5 .5\n2 .5 .5 .5\n")); },
      {"a.dump:9:", "radius"});
  expect_input_error(
      [&] { read_packing(write_file("b.dump", head + "ITEM: ATOMS id x y z radius\n1 .5 .5 .5 .1\n")); },
      {"b.dump", "after line 10", "2 atom lines"});
  expect_input_error([&] { read_packing(write_file("c.dump", head + "ITEM: ATOMS id x y radius\n")); },
                     {"c.dump:9:", "z"});
  expect_input_error(
      [&] {
        read_packing(
            write_file("d.dump", head + "ITEM: ATOMS id x y z radius\n1 .5 .5 .5 .1\n1 .5 .5 .5 .1\n"));
      },
      {"d.dump", "id 1 appears twice"});
  expect_input_error(
      [&] { read_packing(write_file("e.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n")); },
      {"e.dump", "number of atoms"});
}

TEST_F(FormatsTest, ReadsOvitoStyleExtendedXyz) {
  // OVITO/ASE names, species as element symbols, Origin and pbc absent (defaults: 0, periodic).
  const auto path =
      write_file("ovito.xyz",
                 "3\n"
                 "Lattice=\"10.0 0.0 0.0 0.0 11.0 0.0 0.0 0.0 12.0\" Properties=id:I:1:species:S:1:pos:R:3:"
                 "Radius:R:1:velo:R:3:c_cn:I:1:selected:L:1 Time=0.5\n"
                 "10 Si 1 2 3 0.5 0.1 0.2 0.3 4 T\n"
                 "11 O 2 3 4 0.25 0 0 0 5 F\n"
                 "12 Al 3 4 5 0.75 0 0 -1 6 T\n");
  const Packing packing = read_packing(path);
  ASSERT_EQ(packing.size(), 3u);
  EXPECT_EQ(packing.type, (std::vector<int>{2, 1, 0}));  // alphabetical: Al, O, Si
  EXPECT_EQ(packing.radius, (std::vector<double>{0.5, 0.25, 0.75}));
  EXPECT_EQ(packing.velocity[0], (Vec3{0.1, 0.2, 0.3}));
  EXPECT_EQ(packing.box.length, (Vec3{10, 11, 12}));
  EXPECT_EQ(packing.box.lo, (Vec3{0, 0, 0}));
  EXPECT_EQ(packing.box.periodic, (std::array<bool, 3>{true, true, true}));
  ASSERT_NE(packing.field("c_cn"), nullptr);
  EXPECT_EQ(packing.field("c_cn")->values, (std::vector<double>{4, 5, 6}));
  EXPECT_EQ(packing.field("selected")->values, (std::vector<double>{1, 0, 1}));
}

TEST_F(FormatsTest, XyzTypeColumnAndNumericSpecies) {
  const auto path = write_file("t.xyz",
                               "2\nLattice=\"4 0 0 0 4 0 0 0 4\" Origin=\"-2 -2 -2\" pbc=\"1 0 1\" "
                               "Properties=pos:R:3:diameter:R:1:type:I:1:species:S:1\n"
                               "0 0 0 1 7 Fe\n1 1 1 2 3 Ni\n");
  const Packing packing = read_xyz(path, {});
  EXPECT_EQ(packing.type, (std::vector<int>{7, 3}));  // type:I:1 wins over species
  EXPECT_EQ(packing.radius, (std::vector<double>{0.5, 1.0}));
  EXPECT_EQ(packing.box.lo, (Vec3{-2, -2, -2}));
  EXPECT_EQ(packing.box.periodic, (std::array<bool, 3>{true, false, true}));
  const auto numeric =
      write_file("n.xyz", "2\nProperties=species:S:1:pos:R:3:radius:R:1\n2 0 0 0 1\n5 3 0 0 1\n");
  EXPECT_EQ(read_xyz(numeric, {}).type, (std::vector<int>{2, 5}));
}

TEST_F(FormatsTest, XyzWithoutLatticeUsesBoundingBoxOrGivenBox) {
  const auto p2 =
      write_file("b.xyz", "2\nProperties=species:S:1:pos:R:3:radius:R:1\nT0 0 0 0 1\nT1 4 1 0 0.5\n");
  const Packing packing = read_packing(p2);
  EXPECT_EQ(packing.box.lo, (Vec3{-1, -1, -1}));
  EXPECT_EQ(packing.box.length, (Vec3{5.5, 2.5, 2}));
  EXPECT_EQ(packing.box.periodic, (std::array<bool, 3>{false, false, false}));
  Box given;
  given.length = {9, 9, 9};
  expect_same_box(given, read_packing(p2, {.box = given}).box);
}

TEST_F(FormatsTest, XyzErrors) {
  expect_input_error(
      [&] {
        read_packing(write_file(
            "a.xyz",
            "1\nLattice=\"1 0.5 0 0 1 0 0 0 1\" Properties=species:S:1:pos:R:3:radius:R:1\nT0 0 0 0 1\n"));
      },
      {"a.xyz:2:", "not diagonal"});
  expect_input_error(
      [&] {
        read_packing(write_file(
            "b.xyz", "1\nProperties=species:S:1:pos:R:3:radius:R:1:color:R:3\nT0 0 0 0 1 1 1 1\n"));
      },
      {"b.xyz:2:", "color"});
  expect_input_error(
      [&] {
        read_packing(
            write_file("c.xyz", "1\nProperties=species:S:1:pos:R:3:radius:R:1:label:S:1\nT0 0 0 0 1 x\n"));
      },
      {"c.xyz:2:", "label"});
  expect_input_error(
      [&] { read_packing(write_file("d.xyz", "1\nProperties=species:S:1:pos:R:3\nT0 0 0 0\n")); },
      {"d.xyz:2:", "radius"});
  expect_input_error(
      [&] { read_packing(write_file("e.xyz", "1\nProperties=species:S:1:pos:R:3:radius:R:1\nT0 0 0 0\n")); },
      {"e.xyz:3:", "expected 5 columns"});
  expect_input_error(
      [&] { read_packing(write_file("f.xyz", "two\nProperties=species:S:1:pos:R:3:radius:R:1\n")); },
      {"f.xyz:1:", "number of particles"});
  expect_input_error(
      [&] {
        read_packing(
            write_file("g.xyz", "1\nLattice=\"1 0 0 0 1 0 0 0 1 Properties=pos:R:3:radius:R:1\n0 0 0 1\n"));
      },
      {"g.xyz:2:", "closing"});
  Packing packing = random_packing(3, 4);
  packing.field_or_add("bad name");
  expect_input_error([&] { write_xyz(packing, file("w.xyz"), {}); }, {"w.xyz", "bad name"});
  packing.fields.back().name = "radius";
  expect_input_error([&] { write_xyz(packing, file("w.xyz"), {}); }, {"w.xyz", "radius"});
  EXPECT_FALSE(fs::exists(file("w.xyz")));
}

TEST_F(FormatsTest, CsvReadsHeaderInAnyOrderHeaderlessAndShortBox) {
  const auto path = write_file("a.csv", "# box 4 5 6\ntype, radius ,\"x\",y,z\n1,0.5,1,2,3\n0,0.25,2,3,4\n");
  const Packing packing = read_packing(path);
  EXPECT_EQ(packing.type, (std::vector<int>{1, 0}));
  EXPECT_EQ(packing.radius, (std::vector<double>{0.5, 0.25}));
  EXPECT_EQ(packing.position[1], (Vec3{2, 3, 4}));
  EXPECT_EQ(packing.box.length, (Vec3{4, 5, 6}));
  EXPECT_EQ(packing.box.periodic, (std::array<bool, 3>{true, true, true}));
  const Packing headerless = read_packing(write_file("b.csv", "1,2,3,0.5\n2,3,4,0.5\n"));
  EXPECT_EQ(headerless.size(), 2u);
  EXPECT_EQ(headerless.box.periodic, (std::array<bool, 3>{false, false, false}));
  expect_input_error([&] { read_packing(write_file("c.csv", "x,y,z,r,colour\n1,2,3,1,red\n")); },
                     {"c.csv:1:", "colour"});
  expect_input_error([&] { read_packing(write_file("d.csv", "x,y,z,r\n1,2,3\n")); },
                     {"d.csv:2:", "expected 4"});
}

TEST_F(FormatsTest, TextReadsTypeColumnAndLongBoxLine) {
  const auto path = write_file(
      "a.dat", "# made by hand\n# box lo -1 -2 -3 length 4 5 6 periodic T F T\n\n0 0 0 0.5 2\n1 1 1 0.5\n");
  const Packing packing = read_packing(path);
  EXPECT_EQ(packing.type, (std::vector<int>{2, 0}));
  EXPECT_EQ(packing.box.lo, (Vec3{-1, -2, -3}));
  EXPECT_EQ(packing.box.periodic, (std::array<bool, 3>{true, false, true}));
  expect_input_error([&] { read_packing(write_file("b.txt", "# box 1 2\n0 0 0 1\n")); },
                     {"b.txt:1:", "# box"});
}

TEST(BoundingBox, SpansSpheresAndIsOpen) {
  Packing packing;
  packing.add({0, 0, 0}, 1.0);
  packing.add({3, -1, 2}, 0.5);
  const Box box = bounding_box(packing);
  EXPECT_EQ(box.lo, (Vec3{-1, -1.5, -1}));
  EXPECT_EQ(box.length, (Vec3{4.5, 2.5, 3.5}));
  EXPECT_EQ(box.periodic, (std::array<bool, 3>{false, false, false}));
}

// ---------------------------------------------------------------------------------------------
// Error paths shared by every format

TEST_F(FormatsTest, MissingFileIsInputErrorForEveryFormat) {
  for (const char* name : {"none.xyz", "none.vtu", "none.data", "none.dump", "none.csv", "none.txt"}) {
    SCOPED_TRACE(name);
    expect_input_error([&] { read_packing(file(name)); }, {name, "no such file"});
  }
  expect_input_error([&] { read_packing(dir_ / "folder.txt"); }, {"folder.txt"});
}

TEST_F(FormatsTest, MalformedNumberNamesFileAndLine) {
  expect_input_error([&] { read_packing(write_file("a.txt", "# box 1 1 1\n0 0 0 0.1\n0 0 0.5x 0.1\n")); },
                     {"a.txt:3:", "'0.5x'"});
  expect_input_error([&] { read_packing(write_file("a.csv", "x,y,z,r\n0,0,abc,1\n")); },
                     {"a.csv:2:", "'abc'"});
  expect_input_error(
      [&] {
        read_packing(write_file("a.xyz", "1\nProperties=species:S:1:pos:R:3:radius:R:1\nT0 0 0 0 1e\n"));
      },
      {"a.xyz:3:", "'1e'"});
  expect_input_error(
      [&] {
        read_packing(write_file(
            "a.data",
            "t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n1 1 1 1 0.5 0.5 nan?\n"));
      },
      {"a.data:10:", "'nan?'"});
  expect_input_error(
      [&] {
        read_packing(write_file("a.dump",
                                "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n0 "
                                "1\n0 1\n0 1\nITEM: ATOMS x y z radius\n0.5 0.5 0.5 --1\n"));
      },
      {"a.dump:10:", "'--1'"});
  write_vtu(random_packing(5, 3), file("a.vtu"), {});
  std::ifstream in(file("a.vtu"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find("Name=\"radius\"");
  const auto number = text.find('\n', at) + 1;
  text.replace(number, 3, "0.x");
  expect_input_error([&] { read_packing(write_file("b.vtu", text)); }, {"b.vtu:", "'0.x"});
}

TEST_F(FormatsTest, NegativeRadiusIsInputError) {
  expect_input_error([&] { read_packing(write_file("a.txt", "0 0 0 -0.5\n")); }, {"a.txt:1:", "radius"});
  expect_input_error([&] { read_packing(write_file("a.csv", "x,y,z,r\n0,0,0,0\n")); },
                     {"a.csv:2:", "radius"});
  expect_input_error(
      [&] {
        read_packing(write_file("a.xyz", "1\nProperties=species:S:1:pos:R:3:radius:R:1\nT0 0 0 0 -1\n"));
      },
      {"a.xyz:3:", "radius"});
  expect_input_error(
      [&] {
        read_packing(write_file(
            "a.data",
            "t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n1 1 -1 1 0.5 0.5 0.5\n"));
      },
      {"a.data:10:", "diameter"});
  Packing packing = random_packing(6, 3);
  packing.radius[1] = -packing.radius[1];
  expect_input_error([&] { write_packing(packing, file("w.vtu")); }, {"w.vtu", "radius"});
  EXPECT_FALSE(fs::exists(file("w.vtu")));
}

TEST_F(FormatsTest, TruncatedFileIsInputError) {
  const Packing packing = random_packing(7, 10);
  for (const char* name : {"t.xyz", "t.vtu", "t.data"}) {
    SCOPED_TRACE(name);
    write_packing(packing, file(name));
    const auto size = fs::file_size(file(name));
    fs::resize_file(file(name), size * 3 / 10);  // inside the particle data
    expect_input_error([&] { read_packing(file(name)); }, {name});
  }
  expect_input_error([&] { read_packing(write_file("e.xyz", "")); }, {"e.xyz", "line 0"});
  expect_input_error([&] { read_packing(write_file("e.vtu", "")); }, {"e.vtu"});
  expect_input_error([&] { read_packing(write_file("e.data", "")); }, {"e.data"});
  expect_input_error([&] { read_packing(write_file("e.dump", "")); }, {"e.dump"});
  expect_input_error([&] { read_packing(write_file("e.txt", "")); }, {"e.txt", "nor a box"});
  expect_input_error([&] { read_packing(write_file("g.vtu", "\x89PNG\r\n\x1a\n garbage <<<")); }, {"g.vtu:"});
}

// Cutting or corrupting a written file anywhere must give a packing or an InputError, never a
// crash, a hang or another exception.
TEST_F(FormatsTest, DamagedFilesNeverCrash) {
  const Packing packing = random_packing(8, 6);
  for (const char* name : {"d.xyz", "d.vtu", "d.data", "d.csv", "d.txt"}) {
    SCOPED_TRACE(name);
    write_packing(packing, file(name));
    std::ifstream in(file(name), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::mt19937 rng(42);
    for (int trial = 0; trial < 120; ++trial) {
      std::string damaged = text;
      const std::size_t at = rng() % text.size();
      switch (trial % 3) {
        case 0: damaged.resize(at); break;
        case 1: damaged[at] = "<>\"=:# -.e0\n\x01"[rng() % 14]; break;
        case 2: damaged.erase(at, 1 + rng() % 20); break;
      }
      const fs::path path = write_file(std::string("damaged_") + name, damaged);
      try {
        (void)read_packing(path);
      } catch (const InputError&) {
      } catch (const std::exception& other) {
        ADD_FAILURE() << "trial " << trial << ": " << typeid(other).name() << ": " << other.what();
      }
    }
  }
}

TEST_F(FormatsTest, DumpCannotBeWritten) {
  expect_input_error([&] { write_packing(random_packing(9, 2), file("x.dump")); }, {"x.dump", "read-only"});
}

}  // namespace
}  // namespace packlab::io
