#include <gtest/gtest.h>

#include <fstream>
#include <limits>

#include "../cli/cli_runner.hpp"
#include "packlab/core/error.hpp"
#include "packlab/io/config.hpp"
#include "packlab/io/options.hpp"
#include "packlab/mechanics/oscillatory_shear.hpp"
#include "packlab/mechanics/uniaxial_compression.hpp"

using namespace packlab;

namespace {

struct Settings {
  double stiffness = 100.0;
  long steps = 10;
  int threads = 0;
  std::uint64_t seed = 1;
  bool plots = true;
  std::string law = "linear";
  double damping_a = 0.7, damping_b = 0.7;
};

io::ConfigSchema schema(Settings& s) {
  io::ConfigSchema c("demo", "A schema for tests.");
  c.number("material.stiffness", s.stiffness, "k")
      .unit("N/m")
      .range(ranges::positive)
      .integer("relax.steps", s.steps, "steps")
      .alias("steps")
      .integer("threads", s.threads, "threads")
      .integer("seed", s.seed, "seed")
      .boolean("plots", s.plots, "plots")
      .text("law", s.law, "contact | law")
      .number_to_all("damping", {&s.damping_a, &s.damping_b}, "both");
  return c;
}

std::string write(const test::TempDir& dir, const std::string& text) {
  const auto path = dir.path() / "c.toml";
  std::ofstream(path) << text;
  return path.string();
}

std::string error_of(const io::ConfigSchema& c, const std::string& file) {
  try {
    c.read_file(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ConfigSchema, ReadsEveryTypeIntoItsTarget) {
  test::TempDir dir("config");
  Settings s;
  schema(s).read_file(write(dir,
                            "threads = 2\nseed = 99\nplots = false\nlaw = \"hertz\"\ndamping = 0.3\n"
                            "[material]\nstiffness = 5e2\n[relax]\nsteps = 7\n"));
  EXPECT_EQ(s.stiffness, 500.0);
  EXPECT_EQ(s.steps, 7);
  EXPECT_EQ(s.threads, 2);
  EXPECT_EQ(s.seed, 99u);
  EXPECT_FALSE(s.plots);
  EXPECT_EQ(s.law, "hertz");
  EXPECT_EQ(s.damping_a, 0.3);
  EXPECT_EQ(s.damping_b, 0.3);
}

TEST(ConfigSchema, UnknownKeysAndWrongTypesNameFileAndKey) {
  test::TempDir dir("config");
  Settings s;
  const auto c = schema(s);
  std::string e = error_of(c, write(dir, "[material]\nstifness = 1.0\n"));
  EXPECT_NE(e.find("material.stifness"), std::string::npos) << e;
  EXPECT_NE(e.find("known: stiffness"), std::string::npos) << e;
  e = error_of(c, write(dir, "colour = 1\n"));
  EXPECT_NE(e.find("[material]"), std::string::npos) << e;
  EXPECT_NE(error_of(c, write(dir, "threads = 1.5\n")).find("must be an integer"), std::string::npos);
  EXPECT_NE(error_of(c, write(dir, "threads = 99999999999\n")).find("out of range"), std::string::npos);
  EXPECT_NE(error_of(c, write(dir, "seed = -1\n")).find("out of range"), std::string::npos);
  EXPECT_NE(error_of(c, write(dir, "plots = 1\n")).find("true or false"), std::string::npos);
  EXPECT_NE(error_of(c, write(dir, "material = 3\n")).find("must be a table"), std::string::npos);
  EXPECT_NE(error_of(c, write(dir, "law = 3\n")).find("string"), std::string::npos);
  EXPECT_NE(error_of(c, write(dir, "[relax\n")).find("c.toml:1"), std::string::npos);
  EXPECT_NE(error_of(c, (dir.path() / "missing.toml").string()).find("no such file"), std::string::npos);
  // A file with one bad key changes nothing, not even the keys before it.
  EXPECT_NE(error_of(c, write(dir, "threads = 2\nplots = 1\n")).find("plots"), std::string::npos);
  EXPECT_EQ(s.threads, 0);
}

TEST(ConfigSchema, MarkdownListsEveryKeyWithItsDefault) {
  Settings s;
  const std::string md = schema(s).markdown();
  EXPECT_NE(md.find("## `packlab demo`"), std::string::npos);
  EXPECT_NE(md.find("| `material.stiffness` | number | `100` | N/m | > 0 | k |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `law` | string | `\"linear\"` |  |  | contact / law |"), std::string::npos) << md;
}

TEST(ConfigSchema, NamesFlagsKeywordsAndReportEntriesAfterTheKey) {
  Settings s;
  const auto c = schema(s);
  const auto* f = c.find("relax.steps");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->flag(), "--relax-steps");
  EXPECT_EQ(f->keyword(), "relax_steps");
  EXPECT_EQ(c.find("--relax-steps"), f);
  EXPECT_EQ(c.find("relax_steps"), f);
  EXPECT_EQ(c.find("steps"), f);  // the alias
  EXPECT_EQ(c.find("--steps"), f);
  EXPECT_EQ(c.find("relax_stepz"), nullptr);
  const nlohmann::json j = c.json();
  EXPECT_EQ(j["material"]["stiffness_N_per_m"], 100.0);
  EXPECT_EQ(j["relax"]["steps"], 10);
  EXPECT_EQ(j["law"], "linear");
  EXPECT_FALSE(j.contains("damping"));  // number_to_all: its targets report themselves
  EXPECT_EQ(io::unit_suffix("kg/m^3"), "kg_per_m3");
}

TEST(ConfigSchema, TextAndValuesGoThroughOneTypeCheck) {
  Settings s;
  const auto c = schema(s);
  io::ConfigSchema::set_text(*c.find("relax.steps"), "42", "--relax-steps");
  io::ConfigSchema::set_text(*c.find("material.stiffness"), "2.5e2", "--material-stiffness");
  io::ConfigSchema::set_text(*c.find("plots"), "false", "--plots");
  io::ConfigSchema::set(*c.find("damping"), std::int64_t{0}, "damping");
  EXPECT_EQ(s.steps, 42);
  EXPECT_EQ(s.stiffness, 250.0);
  EXPECT_FALSE(s.plots);
  EXPECT_EQ(s.damping_a, 0.0);
  EXPECT_EQ(s.damping_b, 0.0);
  const auto message = [&](const char* key, const std::string& text) {
    try {
      io::ConfigSchema::set_text(*c.find(key), text, key);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("relax.steps", "1.5").find("must be an integer"), std::string::npos);
  EXPECT_NE(message("threads", "99999999999").find("out of range"), std::string::npos);
  EXPECT_NE(message("plots", "maybe").find("true or false"), std::string::npos);
  EXPECT_NE(message("material.stiffness", "stiff").find("must be a number"), std::string::npos);
  try {
    io::ConfigSchema::set(*c.find("law"), 3.0, "law");
    ADD_FAILURE() << "a number for a string";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("string"), std::string::npos);
  }
}

TEST(ConfigSchema, ValidateChecksTheDeclaredRanges) {
  Settings s;
  const auto c = schema(s);
  c.validate();
  s.stiffness = -1.0;
  try {
    c.validate();
    ADD_FAILURE() << "a negative stiffness passed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("material.stiffness = -1: must be > 0 N/m"), std::string::npos) << e.what();
  }
}

TEST(ConfigSchema, CheckedInReferenceMatchesTheBinary) {
  // docs/config-reference.md is generated by `make docs`; it must not drift from the code.
  const auto result = test::run_packlab("config-keys");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::ifstream in(std::string(PACKLAB_SOURCE_DIR) + "/docs/config-reference.md");
  const std::string checked_in((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(checked_in, result.output) << "run `make docs` to regenerate docs/config-reference.md";
}

// values() and set_values(): a run's settings as its checkpoint keeps them, read back exactly.
TEST(ConfigSchema, ValuesRoundTripExactlyAndForeignKeysAreRefused) {
  Settings a;
  a.stiffness = 0.1 + 0.2;  // not a short decimal
  a.steps = 123456789012;
  a.seed = 42;
  a.plots = false;
  a.law = "hertz";
  a.damping_a = a.damping_b = 1.0 / 3.0;
  const nlohmann::json saved = nlohmann::json::parse(schema(a).values().dump());
  Settings b;
  schema(b).set_values(saved, "checkpoint");
  EXPECT_EQ(b.stiffness, a.stiffness);
  EXPECT_EQ(b.steps, a.steps);
  EXPECT_EQ(b.seed, a.seed);
  EXPECT_EQ(b.plots, a.plots);
  EXPECT_EQ(b.law, a.law);
  EXPECT_EQ(b.damping_b, a.damping_b);
  EXPECT_THROW(schema(b).set_values(nlohmann::json{{"no_such_key", 1}}, "checkpoint"), InputError);
  EXPECT_THROW(schema(b).set_values(nlohmann::json{{"plots", "yes"}}, "checkpoint"), InputError);
  EXPECT_THROW(schema(b).set_values(nlohmann::json::array(), "checkpoint"), InputError);
  EXPECT_THROW(schema(b).set_values(nlohmann::json{{"threads", 99999999999}}, "checkpoint"), InputError);
  EXPECT_THROW(schema(b).set_values(nlohmann::json{{"seed", std::numeric_limits<std::uint64_t>::max()}}, "checkpoint"),
               InputError);
  EXPECT_THROW(schema(b).set_values(nlohmann::json{{"threads", 2.5}}, "checkpoint"), InputError);
  EXPECT_THROW(schema(b).set_values(nlohmann::json{{"law", nullptr}}, "checkpoint"), InputError);
}

// A key added after runs were saved: a record without it resumes with the value those runs
// ran with (shakes before move_rule existed used the freest-direction rule), not today's default.
TEST(ConfigSchema, KeysMissingFromASavedRecordTakeTheValueOldRunsRanWith) {
  generate::ShakeParams params;
  ASSERT_EQ(params.move_rule, "metropolis");  // today's default
  io::ConfigSchema shake("shake");
  io::add_shake_params(shake, params);
  nlohmann::json old_record = shake.values();
  old_record.erase("move_rule");
  shake.set_values(old_record, "checkpoint");
  EXPECT_EQ(params.move_rule, "freest");
  nlohmann::json new_record = old_record;
  new_record["move_rule"] = "metropolis";
  shake.set_values(new_record, "checkpoint");
  EXPECT_EQ(params.move_rule, "metropolis");
  // A value that does not fit its field is refused where it is declared.
  std::string rule;
  io::ConfigSchema wrong("shake");
  wrong.text("move_rule", rule, "a rule");
  EXPECT_THROW(wrong.when_not_saved(3), std::logic_error);
  EXPECT_NO_THROW(wrong.when_not_saved("freest"));
  // The same checks as a saved value's: an integer field refuses 2.5 and a count beyond its type.
  Settings s;
  io::ConfigSchema integers("demo");
  integers.integer("threads", s.threads, "threads");
  EXPECT_THROW(integers.when_not_saved(2.5), std::logic_error);
  EXPECT_THROW(integers.when_not_saved(99999999999), std::logic_error);
  EXPECT_NO_THROW(integers.when_not_saved(4));
  EXPECT_EQ(s.threads, 0);  // declaring it sets nothing
}

// adapt_threads (dem::EngineConfig::adapt_threads) is a key of every command that runs the
// explicit engine, default on, and reaches the engine's configuration.
TEST(ConfigSchema, AdaptThreadsReachesEveryEngineRun) {
  test::TempDir dir("config");
  const std::string off = write(dir, "adapt_threads = false\nthreads = 2\n");
  io::RelaxRun relax;
  EXPECT_TRUE(relax.config().adapt_threads);
  io::relax_options(relax).read_file(off);
  EXPECT_FALSE(relax.config().adapt_threads);
  EXPECT_EQ(relax.config().threads, 2);
  mechanics::UniaxialCompressionSetup compress;
  EXPECT_TRUE(mechanics::compression_engine_config(compress.options).adapt_threads);
  io::compression_test_options(compress).read_file(off);
  EXPECT_FALSE(mechanics::compression_engine_config(compress.options).adapt_threads);
  io::ShearTestRun shear;
  EXPECT_TRUE(mechanics::shear_engine_config(shear.test).adapt_threads);
  io::shear_test_options(shear).read_file(off);
  EXPECT_FALSE(mechanics::shear_engine_config(shear.test).adapt_threads);
  generate::VemParams vem;
  EXPECT_TRUE(vem.adapt_threads);
  io::vem_options(vem).read_file(off);
  EXPECT_FALSE(vem.adapt_threads);
  // Like every boolean key: a value of another type names the key.
  EXPECT_NE(error_of(io::relax_options(relax), write(dir, "adapt_threads = 2\n")).find("adapt_threads"),
            std::string::npos);
}

// A range on a list key holds for each of its numbers (validate names the key and the value).
TEST(ConfigSchema, ARangeOnAListOfNumbersChecksEachNumber) {
  std::vector<double> levels{1.0, 2.0};
  io::ConfigSchema c("demo", "A schema for tests.");
  c.numbers("levels", levels, "levels").unit("Pa").range(ranges::positive);
  EXPECT_NO_THROW(c.validate());
  levels = {1.0, -3.0};
  try {
    c.validate();
    ADD_FAILURE() << "a negative level passed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("levels"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("-3"), std::string::npos) << e.what();
  }
}
