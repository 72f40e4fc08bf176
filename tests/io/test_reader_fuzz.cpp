// Mutation fuzzing of every packing reader (xyz, csv, txt, vtu, LAMMPS data, LAMMPS dump).
//
// The seeds are the small valid files in tests/data/fuzz/<format>/. Each mutant is a seed with
// one to a dozen random edits (bit flips, byte replacements, insertions of bytes or format
// keywords, deletions, truncation, duplicated, deleted or swapped lines, numbers replaced by
// edge values, pieces spliced in from another seed of the same format), written to a file with
// the seed's extension and read with read_packing(). The only acceptable outcomes are a packing
// that passes Packing::validate() or an InputError; any other exception fails the test, and a
// crash or a read that takes longer than read_time_limit ends it (abort, naming the file).
//
// Every random choice comes from one std::mt19937_64, so a run is reproducible: the same seed
// and iteration count give the same mutants, and each failing mutant is also kept as a file
// (its path is in the failure message). The default run is short, for every `make test`:
//   PACKLAB_FUZZ_ITERATIONS   mutants per format (default 10,000: about 1 s per format, 60,000 in all)
//   PACKLAB_FUZZ_SEED         the generator's seed (default 20240611)
// e.g. PACKLAB_FUZZ_ITERATIONS=100000 build/packlab_tests --gtest_filter='ReaderFuzz.*'
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <random>
#include <string>
#include <string_view>
#include <thread>
#include <typeinfo>
#include <vector>

#include "io_test_dir.hpp"
#include "packlab/core/error.hpp"
#include "packlab/core/packing.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::io {
namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t default_seed = 20240611;
constexpr std::uint64_t default_iterations = 10000;
// Every seed is a few hundred bytes and reads in well under a millisecond, also under the
// sanitizers; a read this slow is a hang (or a worse than linear parser).
constexpr auto read_time_limit = std::chrono::seconds(20);
// More failures than this and the rest would only repeat them.
constexpr int max_reported_failures = 20;

// The corpus folders, one per reader (read_packing picks the reader from the extension).
const std::array<const char*, 6> formats = {"xyz", "csv", "txt", "vtu", "lammps_data", "lammps_dump"};

fs::path corpus_dir() { return fs::path(PACKLAB_SOURCE_DIR) / "tests" / "data" / "fuzz"; }

std::string file_contents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Seed {
  fs::path path;
  std::string text;
};

// The seed files of one format, in name order (directory order is unspecified, and the order
// decides which mutants a generator seed gives).
std::vector<Seed> load_seeds(const std::string& format) {
  std::vector<fs::path> paths;
  for (const auto& entry : fs::directory_iterator(corpus_dir() / format))
    if (entry.is_regular_file()) paths.push_back(entry.path());
  std::sort(paths.begin(), paths.end());
  std::vector<Seed> seeds;
  for (const auto& path : paths) seeds.push_back({path, file_contents(path)});
  return seeds;
}

// A positive count or seed from the environment, else the default; a malformed value fails
// the test rather than silently running the default.
std::uint64_t from_environment(const char* name, std::uint64_t fallback) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  char* end = nullptr;
  const unsigned long long value = std::strtoull(text, &end, 10);
  if (*end != '\0' || text[0] == '-') {
    ADD_FAILURE() << name << " = '" << text << "': expected a non-negative integer; using " << fallback;
    return fallback;
  }
  return value;
}

// Aborts the test program when one read takes longer than `limit`: a hang must end the run
// with the file named, not wait for ctest's timeout.
class Watchdog {
 public:
  explicit Watchdog(std::chrono::seconds limit) : limit_(limit), thread_([this] { watch(); }) {}
  ~Watchdog() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

  void begin(std::string what) {
    std::lock_guard lock(mutex_);
    what_ = std::move(what);
    started_ = std::chrono::steady_clock::now();
    busy_ = true;
  }
  void end() {
    std::lock_guard lock(mutex_);
    busy_ = false;
  }

 private:
  void watch() {
    std::unique_lock lock(mutex_);
    while (!stop_) {
      wake_.wait_for(lock, std::chrono::milliseconds(200));
      if (busy_ && std::chrono::steady_clock::now() - started_ > limit_) {
        std::fprintf(stderr, "reader fuzz: %s: no result after %lld s (a hang?); the file is kept\n", what_.c_str(),
                     static_cast<long long>(limit_.count()));
        std::fflush(stderr);
        std::abort();
      }
    }
  }

  std::chrono::seconds limit_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  bool busy_ = false;
  std::string what_;
  std::chrono::steady_clock::time_point started_;
  std::thread thread_;  // last: starts after the members it reads
};

// Bytes and tokens that mean something to one of the parsers.
constexpr char special_byte_list[] = "\0\n\r\t #,.-+eE0123456789<>/=\"':!?&;[]{}TFxyz\x7f\x80\xff";
constexpr std::string_view special_bytes(special_byte_list, sizeof(special_byte_list) - 1);
const std::vector<std::string> keywords = {
    "#", "# box ", "box lo ", " length ", " periodic ", "T T F", "x,y,z,r", "radius", "diameter", "type",
    // extended XYZ
    "Lattice=\"", "Origin=\"", "pbc=\"", "Properties=", ":R:1", ":R:3", ":I:1", ":S:1", ":L:1", "pos:R:3",
    "species:S:1", "velo:R:3", "\"",
    // LAMMPS
    "ITEM: ", "ITEM: ATOMS ", "ITEM: BOX BOUNDS ", "ITEM: NUMBER OF ATOMS\n", "pp ", "ff ", "xy xz yz ", " atoms\n",
    " atom types\n", " xlo xhi", "\nAtoms # sphere\n\n", "\nVelocities\n\n", "\nBonds\n\n", "xs", "xu", "id",
    // XML / VTU
    "<", ">", "</", "/>", "<!--", "-->", "<![CDATA[", "]]>", "<?xml", "?>", "&amp;", "&#x41;", "&lt;",
    "<DataArray type=\"Float64\" Name=\"radius\" format=\"ascii\">", "</DataArray>", "NumberOfComponents=\"3\"",
    "NumberOfPoints=\"", "<InformationKey>", "</InformationKey>", "format=\"binary\"", "<Piece>", "</Piece>",
    "<PointData>", "<CellData>", "Name=\"box_lo\"", "type=\"Int32\"", "type=\"UInt8\""};
// Replacements for a number: edge values of double and integer parsing and of the checks.
const std::vector<std::string> edge_numbers = {"0",
                                               "-0",
                                               "1",
                                               "-1",
                                               "2",
                                               "3",
                                               "0.5",
                                               "1e-9",
                                               "nan",
                                               "-nan",
                                               "NaN",
                                               "inf",
                                               "-inf",
                                               "Infinity",
                                               "1e308",
                                               "1.8e308",
                                               "-1e308",
                                               "4.9e-324",
                                               "1e-320",
                                               "1e999",
                                               "2147483647",
                                               "2147483648",
                                               "-2147483648",
                                               "-2147483649",
                                               "4294967296",
                                               "9223372036854775807",
                                               "9223372036854775808",
                                               "-9223372036854775809",
                                               "18446744073709551616",
                                               "1000000000",
                                               "100000000000000",
                                               "1e9",
                                               "1e18",
                                               "0x10",
                                               "0x1p3",
                                               "+5",
                                               ".",
                                               "-",
                                               "+",
                                               "e",
                                               "1e",
                                               "1.2.3",
                                               "--1",
                                               "00000000000000000000000000000001",
                                               "",
                                               " ",
                                               "1 2",
                                               "1,2"};

class Mutator {
 public:
  explicit Mutator(std::uint64_t seed) : rng_(seed) {}

  // A number in [0, n) (0 when n is 0). Modulo rather than a std distribution: mt19937_64's
  // output is fixed by the standard, so the mutants are the same with every standard library.
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng_() % n); }
  bool one_in(std::size_t n) { return below(n) == 0; }

  // The seed `text` with 1..3 edits (1 in 8: 5..12), `others` being the seeds of its format.
  std::string mutate(std::string text, const std::vector<Seed>& others) {
    const std::size_t edits = one_in(8) ? 5 + below(8) : 1 + below(3);
    for (std::size_t e = 0; e < edits; ++e) edit(text, others);
    return text;
  }

 private:
  char random_byte() { return one_in(2) ? special_bytes[below(special_bytes.size())] : static_cast<char>(below(256)); }

  static std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::size_t begin = 0;
    while (begin < text.size()) {
      std::size_t end = text.find('\n', begin);
      end = end == std::string::npos ? text.size() : end + 1;
      lines.push_back(text.substr(begin, end - begin));
      begin = end;
    }
    return lines;
  }
  static std::string join(const std::vector<std::string>& lines) {
    std::string text;
    for (const auto& line : lines) text += line;
    return text;
  }

  // [begin, end) of every maximal run of number characters that holds a digit.
  static std::vector<std::pair<std::size_t, std::size_t>> numbers(const std::string& text) {
    std::vector<std::pair<std::size_t, std::size_t>> found;
    const auto is_number_char = [](char c) {
      return (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' || c == 'e' || c == 'E';
    };
    std::size_t i = 0;
    while (i < text.size()) {
      if (!is_number_char(text[i])) {
        ++i;
        continue;
      }
      std::size_t end = i;
      bool digit = false;
      for (; end < text.size() && is_number_char(text[end]); ++end)
        if (text[end] >= '0' && text[end] <= '9') digit = true;
      if (digit) found.emplace_back(i, end);
      i = end;
    }
    return found;
  }

  std::string new_number(std::string_view old) {
    switch (below(6)) {
      case 0:
        return fmt::format("-{}", old);
      case 1:
        return fmt::format("{}{}", old, below(10));  // one more digit
      case 2:
        return fmt::format("{}e{}", old, static_cast<int>(below(700)) - 350);
      case 3:
        return std::string(1 + below(400), static_cast<char>('0' + below(10)));  // very long
      default:
        return edge_numbers[below(edge_numbers.size())];
    }
  }

  void edit(std::string& text, const std::vector<Seed>& others) {
    switch (below(11)) {
      case 0:  // flip one bit
        if (!text.empty()) text[below(text.size())] ^= static_cast<char>(1u << below(8));
        break;
      case 1:  // replace one byte
        if (!text.empty()) text[below(text.size())] = random_byte();
        break;
      case 2: {  // insert 1..8 bytes
        const std::size_t at = below(text.size() + 1);
        std::string bytes;
        for (std::size_t n = 1 + below(8); n > 0; --n) bytes += random_byte();
        text.insert(at, bytes);
        break;
      }
      case 3:  // insert a keyword
        text.insert(below(text.size() + 1), keywords[below(keywords.size())]);
        break;
      case 4:  // delete 1..32 bytes
        if (!text.empty()) {
          const std::size_t at = below(text.size());
          text.erase(at, 1 + below(std::min<std::size_t>(32, text.size() - at)));
        }
        break;
      case 5:  // truncate
        text.resize(below(text.size() + 1));
        break;
      case 6: {  // duplicate a line (next to itself or elsewhere)
        auto lines = split_lines(text);
        if (lines.empty()) break;
        const std::size_t from = below(lines.size());
        const std::size_t to = one_in(2) ? from : below(lines.size() + 1);
        const std::string copy = lines[from];
        lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(to), copy);
        text = join(lines);
        break;
      }
      case 7: {  // delete or swap lines
        auto lines = split_lines(text);
        if (lines.empty()) break;
        const std::size_t a = below(lines.size());
        if (one_in(2))
          lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(a));
        else
          std::swap(lines[a], lines[below(lines.size())]);
        text = join(lines);
        break;
      }
      case 8:
      case 9: {  // a number edited: counts, coordinates, radii, box bounds, ids, types
        const auto found = numbers(text);
        if (found.empty()) break;
        const auto [begin, end] = found[below(found.size())];
        text.replace(begin, end - begin, new_number(std::string_view(text).substr(begin, end - begin)));
        break;
      }
      case 10: {  // splice: a piece of a seed of the same format inserted or replacing a piece
        const std::string& donor = others[below(others.size())].text;
        if (donor.empty()) break;
        const std::size_t from = below(donor.size());
        const std::string piece = donor.substr(from, 1 + below(std::min<std::size_t>(200, donor.size() - from)));
        const std::size_t at = below(text.size() + 1);
        text.replace(at, one_in(2) ? 0 : below(text.size() - at + 1), piece);
        break;
      }
      default:
        break;
    }
  }

  std::mt19937_64 rng_;
};

struct Outcome {
  bool read = false;    // a packing came back (and passed validate() unless `failure` says so)
  std::string failure;  // empty for the acceptable outcomes: a valid packing or an InputError
};

Outcome read_mutant(const fs::path& path, const ReadOptions& options) {
  try {
    const Packing packing = read_packing(path, options);
    try {
      packing.validate();
    } catch (const InputError& error) {
      return {true, fmt::format("read without error, but validate() fails: {}", error.what())};
    }
    return {true, ""};
  } catch (const InputError&) {
    return {false, ""};
  } catch (const std::exception& error) {
    return {false, fmt::format("{} instead of InputError: {}", typeid(error).name(), error.what())};
  } catch (...) {
    return {false, "an exception that is not a std::exception"};
  }
}

class ReaderFuzz : public IoTestDir {};

// The seeds themselves read: mutants of valid files reach far deeper into a parser than
// mutants of garbage.
TEST_F(ReaderFuzz, EverySeedFileReads) {
  for (const char* format : formats) {
    const auto seeds = load_seeds(format);
    EXPECT_GE(seeds.size(), 2u) << corpus_dir() / format;
    for (const auto& seed : seeds) {
      const Outcome outcome = read_mutant(seed.path, {});
      EXPECT_TRUE(outcome.read) << seed.path << " is refused";
      EXPECT_EQ(outcome.failure, "") << seed.path;
    }
  }
}

TEST_F(ReaderFuzz, EveryMutantReadsOrIsRefusedWithAnInputError) {
  const std::uint64_t seed = from_environment("PACKLAB_FUZZ_SEED", default_seed);
  const std::uint64_t iterations = from_environment("PACKLAB_FUZZ_ITERATIONS", default_iterations);
  const fs::path kept = fs::path(::testing::TempDir()) / "packlab_reader_fuzz_failures";
  Mutator mutator(seed);
  Watchdog watchdog(read_time_limit);
  int failures = 0;
  for (const char* format : formats) {
    const auto seeds = load_seeds(format);
    ASSERT_FALSE(seeds.empty()) << corpus_dir() / format;
    std::uint64_t tried = 0;
    std::uint64_t read = 0;
    for (std::uint64_t i = 0; i < iterations && failures < max_reported_failures; ++i, ++tried) {
      const Seed& original = seeds[mutator.below(seeds.size())];
      const std::string mutant = mutator.mutate(original.text, seeds);
      // Now and then a box from the caller, which replaces the file's (another path through
      // finish_reading).
      ReadOptions options;
      if (mutator.one_in(10)) {
        Box box;
        box.lo = {-1, -1, -1};
        box.length = {10, 10, 10};
        box.periodic = {mutator.one_in(2), mutator.one_in(2), mutator.one_in(2)};
        options.box = box;
      }
      const fs::path path = write_file(fmt::format("mutant{}", original.path.extension().string()), mutant);
      watchdog.begin(
          fmt::format("{} (mutant {} of {}, seed {})", path.string(), i, original.path.filename().string(), seed));
      const Outcome outcome = read_mutant(path, options);
      watchdog.end();
      if (!outcome.failure.empty()) {
        ++failures;
        fs::create_directories(kept);
        const fs::path copy = kept / fmt::format("{}-seed{}-{}{}", format, seed, i, original.path.extension().string());
        fs::copy_file(path, copy, fs::copy_options::overwrite_existing);
        ADD_FAILURE() << format << " mutant " << i << " of " << original.path.filename() << " (kept as " << copy
                      << "): " << outcome.failure;
      } else if (outcome.read) {
        ++read;
      }
      // Removed rather than overwritten: ext4 flushes a file truncated and rewritten when it is
      // closed (auto_da_alloc), which made the run ten times slower.
      fs::remove(path);
    }
    std::printf("reader fuzz: %-12s %llu mutants, %llu read, the rest refused with an InputError\n", format,
                static_cast<unsigned long long>(tried), static_cast<unsigned long long>(read));
  }
}

}  // namespace
}  // namespace packlab::io
