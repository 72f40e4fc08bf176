// Reading and writing packings, chosen by file extension:
//   .xyz .extxyz          extended XYZ (Lattice=, pbc=, Properties=), opens in OVITO
//   .vtu                  VTK unstructured grid (particles as vertices, bonds as lines), ParaView
//   .data .lmp            LAMMPS data file, atom_style sphere (id type diameter density x y z)
//   .dump .lammpstrj      LAMMPS dump (read only): id type x y z radius columns in any order
//   .csv                  x,y,z,r[,type] with the box in a '# box' header comment
//   .txt .dat             plain 'x y z r' lines with an optional '# box Lx Ly Lz' line
//                         (PackingGeneration / ../shared/data/anchor-packings); a fifth
//                         column holds the type when any is nonzero
// LAMMPS's habit of naming files data.<name> and dump.<name> is recognised too. Each format's
// .cpp file starts with the exact layout it writes and what its reader accepts.
// Every writer is atomic and stores doubles with 17 significant digits, so a round trip
// preserves every field exactly. Readers throw InputError naming file, line and problem.
// Every reader rejects (Packing::validate and detail::finish_reading, shared by all formats):
// non-finite box bounds, coordinates, radii, velocities and densities; a particle count in a
// header that differs from the number of particle rows; self-bonds and bonds listed twice; and
// a particle lying outside an open (non-periodic) side of the box by more than its radius +
// 1e-9 of that box edge (detail::open_box_tolerance). Writers widen an open axis whose box
// such a particle has left, so that their files always read back.
#pragma once

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "packlab/core/packing.hpp"

namespace packlab::io {

enum class Format { xyz, vtu, lammps_data, lammps_dump, csv, text };

// InputError for an unknown extension (listing the known ones).
Format format_from_path(const std::filesystem::path& path);
std::string format_name(Format format);

struct ReadOptions {
  // For files without a box (or to override it): the box to use. Without it, files that
  // carry no box get the bounding box of the spheres, open on every axis.
  std::optional<Box> box;
};

// Free-text provenance written into file headers where the format has a place for it
// (version, seed, parameters).
struct WriteOptions {
  std::string comment;
};

Packing read_packing(const std::filesystem::path& path, const ReadOptions& options = {});
void write_packing(const Packing& packing, const std::filesystem::path& path,
                   const WriteOptions& options = {});

// Per-format functions (used by the dispatchers above; public for tests and the Python module).
Packing read_xyz(const std::filesystem::path& path, const ReadOptions& options);
void write_xyz(const Packing& packing, const std::filesystem::path& path, const WriteOptions& options);
Packing read_vtu(const std::filesystem::path& path, const ReadOptions& options);
void write_vtu(const Packing& packing, const std::filesystem::path& path, const WriteOptions& options);
Packing read_lammps_data(const std::filesystem::path& path, const ReadOptions& options);
void write_lammps_data(const Packing& packing, const std::filesystem::path& path,
                       const WriteOptions& options);
Packing read_lammps_dump(const std::filesystem::path& path, const ReadOptions& options);
Packing read_csv(const std::filesystem::path& path, const ReadOptions& options);
void write_csv(const Packing& packing, const std::filesystem::path& path, const WriteOptions& options);
Packing read_text(const std::filesystem::path& path, const ReadOptions& options);
void write_text(const Packing& packing, const std::filesystem::path& path, const WriteOptions& options);

// Bounding box of the spheres (centre +- radius), open on every axis. An empty packing gives a
// zero-size box at the origin (which validate() rejects: a file without particles needs a box).
Box bounding_box(const Packing& packing);

// Pieces shared by the per-format readers and writers (packing_io.cpp); not part of the API.
namespace detail {

// Reads a text file line by line, counting lines, so that every reader reports problems the
// same way: "<file>:<line>: <what was expected>". Streams, so a long dump is never held whole.
class LineReader {
 public:
  explicit LineReader(const std::filesystem::path& path);  // InputError if it cannot be opened

  // Moves to the next line (a trailing '\r' is dropped); false at the end of the file.
  bool next_line();
  std::string_view line() const { return line_; }
  std::size_t line_number() const { return line_number_; }
  const std::filesystem::path& path() const { return path_; }

  [[noreturn]] void fail(std::string_view message) const;                 // names the current line
  [[noreturn]] void fail_end_of_file(std::string_view expected) const;    // "file ends after line N"
  // fail() unless a finite number (every coordinate, radius, box bound, velocity, density).
  double to_double(std::string_view token, std::string_view what) const;
  // Any number, nan and inf included: extra per-particle fields, where NaN marks a missing value.
  double to_value(std::string_view token, std::string_view what) const;
  int to_int(std::string_view token, std::string_view what) const;        // fail() unless an int

 private:
  std::filesystem::path path_;
  std::ifstream stream_;
  std::string line_;
  std::size_t line_number_ = 0;
};

// Whole-token conversions (a leading '+' is allowed); nullopt unless every character is used.
std::optional<double> parse_double(std::string_view token);
std::optional<long long> parse_integer(std::string_view token);
// T/F, 1/0, true/false (any case).
std::optional<bool> parse_flag(std::string_view token);

std::string_view trim(std::string_view text);
std::vector<std::string_view> split(std::string_view text, std::string_view separators = " \t");
std::string to_lower(std::string_view text);
// A token quoted in an error message: at most 40 characters, unprintable bytes shown as '?'.
std::string quote_token(std::string_view token);
// Free text on one line (newlines and tabs become spaces), for header comments.
std::string single_line(std::string_view text);

// The '# box' comment of the text and CSV formats, without the leading '#':
//   box Lx Ly Lz                                        lo = 0, periodic on every axis
//   box lo X Y Z length Lx Ly Lz periodic T T F           any box
// Returns nullopt when the comment is not a box line; fails on a malformed one.
std::optional<Box> parse_box_comment(std::string_view comment, const LineReader& reader);
// For the column formats (csv, txt): true if `line` is a comment ('#'); a '# box' comment is
// read into `box` (a second one is an error).
bool read_comment_line(std::string_view line, const LineReader& reader, std::optional<Box>& box);
// Short form when allowed and lo = 0 and periodic on every axis, else the long form.
std::string format_box_comment(const Box& box, bool allow_short_form);

// Writer side: validate() with the file named in the message.
void validate_for_writing(const Packing& packing, const std::filesystem::path& path);
// Writer side: InputError unless every extra field name is non-empty, unique, free of the
// `forbidden` characters and not one of the format's own names (`reserved`, any case), so
// that the reader gets every field back under its name.
void check_field_names(const Packing& packing, const std::filesystem::path& path,
                       const std::vector<std::string_view>& reserved, std::string_view forbidden);
// Reader side: applies ReadOptions.box, else the file's box, else the bounding box, then
// validate() and check_inside_open_box() with the file named in the message. `lines` (empty or
// one per particle, in packing order) gives the line of each particle for the message.
void finish_reading(Packing& packing, const std::optional<Box>& file_box, const ReadOptions& options,
                    const std::filesystem::path& path, const std::vector<std::size_t>& lines = {});
// How far a sphere may lie outside an open (non-periodic) side of the box, as a fraction of that
// box edge, beyond touching it from outside: a particle whose centre is more than its radius
// + open_box_tolerance * L outside the box along an open axis is rejected by every reader.
inline constexpr double open_box_tolerance = 1e-9;
// The first particle that the rule above rejects (and the axis), or nullopt.
struct OutsideOpenBox {
  std::size_t particle = 0;
  int axis = 0;
};
std::optional<OutsideOpenBox> first_outside_open_box(const Packing& packing);
// Writer side: the box to write. packing.box, unless a particle lies outside an open side (a
// DEM run may let particles leave an open box); then that axis is widened to enclose every
// sphere, so that whatever packlab writes reads back.
Box box_for_writing(const Packing& packing);
// LAMMPS readers: `order` = atom indices sorted by id (LAMMPS writes atoms in processor order);
// InputError naming `path` on a repeated id.
void sort_by_id(std::vector<std::size_t>& order, const std::vector<long long>& ids,
                const std::filesystem::path& path);

}  // namespace detail

}  // namespace packlab::io
