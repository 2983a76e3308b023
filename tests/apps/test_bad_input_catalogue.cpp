// The bad-input catalogue (tests/bad-input/catalogue.yaml): every case run
// through the rigflex binary as a user would, with its exit code, the
// message fragment, the FILE:LINE the error must name, and nothing written
// to the output folder.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "cli_support.hpp"

namespace rigflex::test {
namespace {

const fs::path kCatalogue = fs::path(RIGFLEX_SOURCE_DIR) / "tests" / "bad-input";

struct BadInputCase {
  std::string file, run, message;
  int exit = 0, line = 0;
  bool writes = false;
};

void PrintTo(const BadInputCase& c, std::ostream* os) { *os << c.file << ": " << c.run; }

std::vector<BadInputCase> load_catalogue() {
  std::vector<BadInputCase> out;
  for (const auto& c : YAML::LoadFile((kCatalogue / "catalogue.yaml").string())["cases"]) {
    BadInputCase x;
    x.file = c["file"].as<std::string>();
    x.run = c["run"].as<std::string>();
    x.exit = c["exit"].as<int>();
    x.message = c["message"].as<std::string>();
    x.line = c["line"] ? c["line"].as<int>() : 0;
    x.writes = c["writes"] ? c["writes"].as<bool>() : false;
    out.push_back(x);
  }
  return out;
}

std::string replaced(std::string s, const std::string& what, const std::string& with) {
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + with.size())) {
    s.replace(at, what.size(), with);
  }
  return s;
}

bool holds_nothing(const fs::path& dir) { return !fs::exists(dir) || fs::is_empty(dir); }

class BadInputCatalogue : public ::testing::TestWithParam<BadInputCase> {};

TEST_P(BadInputCatalogue, GivesItsOutcome) {
  const BadInputCase& c = GetParam();
  const fs::path file = kCatalogue / c.file;
  ASSERT_TRUE(fs::exists(file)) << file;
  const fs::path out = fresh_dir("catalogue_" + fs::path(c.file).stem().string());
  std::string args = replaced(c.run, "FILE", "'" + file.string() + "'");
  args = replaced(replaced(args, "OUT", "'" + out.string() + "'"), "DIR/", kCatalogue.string() + "/");
  const CliRun r = run(args);
  EXPECT_EQ(r.code, c.exit) << args << "\n" << r.out;
  EXPECT_NE(r.out.find(c.message), std::string::npos) << "expected \"" << c.message << "\" in:\n" << r.out;
  if (c.line > 0) {
    const std::string at = c.file + ":" + std::to_string(c.line) + ":";
    EXPECT_NE(r.out.find(at), std::string::npos) << "expected " << at << " in:\n" << r.out;
  }
  if (c.writes) {
    EXPECT_FALSE(holds_nothing(out)) << "the control wrote nothing to " << out;
  } else {
    EXPECT_TRUE(holds_nothing(out)) << "a refused run left files in " << out;
  }
  fs::remove_all(out);
}

std::string case_name(const ::testing::TestParamInfo<BadInputCase>& info) {
  std::string s = std::to_string(info.index) + "_" + fs::path(info.param.file).stem().string();
  for (char& ch : s) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return s;
}

INSTANTIATE_TEST_SUITE_P(Catalogue, BadInputCatalogue, ::testing::ValuesIn(load_catalogue()), case_name);

}  // namespace
}  // namespace rigflex::test
