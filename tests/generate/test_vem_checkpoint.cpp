// A damaged VEM checkpoint: every flipped byte is an InputError (checksum), never a crash or a
// resumed run with a different result; an intact one resumes.
#include <gtest/gtest.h>

#include <sstream>

#include "packlab/core/binary_io.hpp"
#include "packlab/core/error.hpp"
#include "packlab/generate/vem.hpp"
#include "small_vem.hpp"

using namespace packlab;
using namespace packlab::generate;

TEST(VemCheckpoint, EveryFlippedByteIsAnInputError) {
  Vem vem(test::small_vem(40, 20, 0.3, 0.2, 200));
  vem.run(300);
  std::ostringstream out;
  vem.save_checkpoint(out);
  const std::string bytes = out.str();
  {
    std::istringstream in(bytes);
    EXPECT_NO_THROW(Vem::resume(in));
  }
  // Every 97th byte (header, sizes, hash, parameters, curve, engine state).
  int checked = 0;
  for (std::size_t k = 0; k < bytes.size(); k += 97, ++checked) {
    std::string damaged = bytes;
    damaged[k] = static_cast<char>(damaged[k] ^ 0x10);
    std::istringstream in(damaged);
    EXPECT_THROW(Vem::resume(in), InputError) << "byte " << k << " of " << bytes.size();
  }
  EXPECT_GT(checked, 20);
  std::istringstream truncated(bytes.substr(0, bytes.size() / 2));
  EXPECT_THROW(Vem::resume(truncated), InputError);
}

TEST(BinaryIo, CheckedSectionRoundTripsAndDetectsDamage) {
  std::ostringstream out;
  binary::write_checked(out, [](std::ostream& s) { binary::write_string(s, "packlab"); });
  std::string bytes = out.str();
  std::istringstream good(bytes);
  std::istringstream section = binary::read_checked(good, "test");
  std::string text;
  binary::read_string(section, text, "text");
  EXPECT_EQ(text, "packlab");
  bytes.back() = 'X';
  std::istringstream bad(bytes);
  EXPECT_THROW(binary::read_checked(bad, "test"), InputError);
}
