// The parameter file: round trip and errors that name the key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/acst_model.h"
#include "toyoura.h"

namespace model::acst {
namespace {

using testing::toyoura;

// One name per process: ctest runs the tests of this file in parallel processes, which would
// otherwise write and read the same file at once.
std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "calibration_" + std::to_string(::getpid()) + "_" + name + ".json";
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

// The error message of read_parameters_json, or "" when it does not throw; the file is removed.
std::string read_error(const std::string& text) {
  const std::string path = temp_path("bad");
  write_text(path, text);
  std::string message;
  try {
    read_parameters_json(path);
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  std::remove(path.c_str());
  return message;
}

std::string valid_text(const std::string& replace_key = "", const std::string& entry = "") {
  const Parameters<double> p = toyoura();
  const std::pair<const char*, double> fields[] = {
      {"G0", p.G0},   {"nu", p.nu},   {"M_c", p.M_c}, {"c", p.c},     {"e_gamma", p.e_gamma},
      {"lambda_c", p.lambda_c},       {"xi", p.xi},   {"m", p.m},     {"h0", p.h0},
      {"c_h", p.c_h}, {"n_b", p.n_b}, {"A0", p.A0},   {"n_d", p.n_d}, {"e_A", p.e_A},
      {"k_F", p.k_F}};
  std::string text = "{\"model\": \"acst\", \"parameters\": {";
  bool first = true;
  for (const auto& [name, value] : fields) {
    std::string item;
    if (name == replace_key) {
      if (entry.empty()) continue;  // drop the key
      item = "\"" + std::string(name) + "\": " + entry;
    } else {
      item = "\"" + std::string(name) + "\": {\"value\": " + std::to_string(value) +
             ", \"unit\": \"1\"}";
    }
    text += (first ? "" : ", ") + item;
    first = false;
  }
  return text + "}}";
}

TEST(ParametersJson, RoundTripIsExact) {
  Parameters<double> p = toyoura();
  p.h0 = 7.051234567890123;  // not representable in few digits
  const std::string path = temp_path("round_trip");
  write_parameters_json(p, path);
  const Parameters<double> q = read_parameters_json(path);
  EXPECT_EQ(q.G0, p.G0);
  EXPECT_EQ(q.nu, p.nu);
  EXPECT_EQ(q.M_c, p.M_c);
  EXPECT_EQ(q.c, p.c);
  EXPECT_EQ(q.e_gamma, p.e_gamma);
  EXPECT_EQ(q.lambda_c, p.lambda_c);
  EXPECT_EQ(q.xi, p.xi);
  EXPECT_EQ(q.m, p.m);
  EXPECT_EQ(q.h0, p.h0);
  EXPECT_EQ(q.c_h, p.c_h);
  EXPECT_EQ(q.n_b, p.n_b);
  EXPECT_EQ(q.A0, p.A0);
  EXPECT_EQ(q.n_d, p.n_d);
  EXPECT_EQ(q.e_A, p.e_A);
  EXPECT_EQ(q.k_F, p.k_F);
  EXPECT_EQ(q.n_b_loose, p.n_b_loose);
  EXPECT_EQ(q.n_G, p.n_G);
  EXPECT_EQ(q.n_F, p.n_F);
  std::remove(path.c_str());
}

// n_b_loose, n_G and n_F came after the first parameter files: a file without them is the model
// it was written for (n_b_loose = 0, n_G = 1/2, n_F = 0); given, they are read and checked like
// the others.
TEST(ParametersJson, ParametersAddedLaterMayBeAbsentAndAreReadWhereGiven) {
  const std::string path = temp_path("added_later");
  // The valid file with one more entry {"value": value, "unit": "1"}.
  auto with = [](const std::string& name, const std::string& value) {
    std::string text = valid_text();
    text.insert(text.rfind("}}"),
                ", \"" + name + "\": {\"value\": " + value + ", \"unit\": \"1\"}");
    return text;
  };
  auto read = [&](const std::string& text) {
    write_text(path, text);
    return read_parameters_json(path);
  };
  EXPECT_EQ(read(valid_text()).n_b_loose, 0.0);
  EXPECT_EQ(read(valid_text()).n_G, 0.5);
  EXPECT_EQ(read(valid_text()).n_F, 0.0);
  EXPECT_EQ(read(with("n_F", "12.5")).n_F, 12.5);
  EXPECT_EQ(read(with("n_b_loose", "7.5")).n_b_loose, 7.5);
  EXPECT_EQ(read(with("n_G", "0.25")).n_G, 0.25);
  const std::string negative = read_error(with("n_b_loose", "-1"));
  EXPECT_NE(negative.find("'n_b_loose'"), std::string::npos) << negative;
  const std::string at_one = read_error(with("n_G", "1"));
  EXPECT_NE(at_one.find("'n_G'"), std::string::npos) << at_one;
  const std::string negative_rate = read_error(with("n_F", "-2"));
  EXPECT_NE(negative_rate.find("'n_F'"), std::string::npos) << negative_rate;
  const std::string huge_rate = read_error(with("n_F", "1e4"));  // exp(-n_F psi) would overflow
  EXPECT_NE(huge_rate.find("'n_F'"), std::string::npos) << huge_rate;
  std::remove(path.c_str());
}

TEST(ParametersJson, HandWrittenFileIsRead) {
  EXPECT_EQ(read_error(valid_text()), "");
}

TEST(ParametersJson, MissingKeyIsNamed) {
  const std::string e = read_error(valid_text("h0"));
  EXPECT_NE(e.find("missing key 'parameters.h0'"), std::string::npos) << e;
  const std::string unit = read_error(valid_text("xi", "{\"value\": 0.7}"));
  EXPECT_NE(unit.find("'parameters.xi.unit'"), std::string::npos) << unit;
  const std::string value = read_error(valid_text("m", "{\"unit\": \"1\"}"));
  EXPECT_NE(value.find("'parameters.m.value'"), std::string::npos) << value;
  EXPECT_NE(read_error("{\"model\": \"acst\"}").find("'parameters'"), std::string::npos);
}

TEST(ParametersJson, NonPhysicalValuesAreNamed) {
  const std::string nu = read_error(valid_text("nu", "{\"value\": 0.5, \"unit\": \"1\"}"));
  EXPECT_NE(nu.find("'nu'"), std::string::npos) << nu;
  EXPECT_NE(nu.find("(-1, 0.5)"), std::string::npos) << nu;
  const std::string nu_low = read_error(valid_text("nu", "{\"value\": -1.0, \"unit\": \"1\"}"));
  EXPECT_NE(nu_low.find("'nu'"), std::string::npos) << nu_low;
  const std::string g0 = read_error(valid_text("G0", "{\"value\": 0, \"unit\": \"1\"}"));
  EXPECT_NE(g0.find("'G0'"), std::string::npos) << g0;
  const std::string mc = read_error(valid_text("M_c", "{\"value\": -1.25, \"unit\": \"1\"}"));
  EXPECT_NE(mc.find("'M_c'"), std::string::npos) << mc;
  const std::string unit = read_error(valid_text("G0", "{\"value\": 125, \"unit\": \"kPa\"}"));
  EXPECT_NE(unit.find("'parameters.G0.unit'"), std::string::npos) << unit;
  const std::string text = read_error(valid_text("c", "{\"value\": \"0.7\", \"unit\": \"1\"}"));
  EXPECT_NE(text.find("'parameters.c.value' must be a number"), std::string::npos) << text;
  // Overflowing and not-a-number values: refused at load time, naming the file and the key.
  const std::string huge = read_error(valid_text("h0", "{\"value\": 1e400, \"unit\": \"1\"}"));
  EXPECT_NE(huge.find("number overflow parsing '1e400'"), std::string::npos) << huge;
  EXPECT_NE(huge.find(temp_path("bad")), std::string::npos) << huge;
  const std::string nan = read_error(valid_text("k_F", "{\"value\": NaN, \"unit\": \"1\"}"));
  EXPECT_NE(nan.find(temp_path("bad")), std::string::npos) << nan;
  EXPECT_NE(nan.find("not valid JSON"), std::string::npos) << nan;
  const std::string nan_text =
      read_error(valid_text("k_F", "{\"value\": \"nan\", \"unit\": \"1\"}"));
  EXPECT_NE(nan_text.find("'parameters.k_F.value' must be a number"), std::string::npos)
      << nan_text;
}

TEST(ParametersJson, BrokenFilesAreReported) {
  EXPECT_NE(read_error("{\"parameters\": ").find("not valid JSON"), std::string::npos);
  EXPECT_THROW(read_parameters_json(temp_path("does_not_exist")), std::runtime_error);
  Parameters<double> p = toyoura();
  p.nu = 0.7;
  EXPECT_THROW(write_parameters_json(p, temp_path("invalid")), std::runtime_error);
}

// The one parameter table (kParameterFields) against docs/model.md §5: every parameter listed in
// order, with the unit, the valid range validate_parameters enforces and the fit's search range.
TEST(ParameterTable, DocsListEveryParameterAsTheCodeDoes) {
  std::ifstream docs(std::string(SFFCAL_SOURCE_DIR) + "/docs/model.md");
  ASSERT_TRUE(docs) << "docs/model.md";
  std::vector<std::vector<std::string>> rows;
  bool in_table = false;
  for (std::string line; std::getline(docs, line);) {
    if (line.rfind("| symbol (key) | unit |", 0) == 0) in_table = true;
    else if (in_table && line.rfind("|", 0) != 0) break;
    if (!in_table || line.rfind("|---", 0) == 0 || line.rfind("| symbol", 0) == 0) continue;
    std::vector<std::string> cells;
    for (std::size_t start = 1, bar; (bar = line.find(" |", start)) != std::string::npos; start = bar + 2)
      cells.push_back(line.substr(start + 1, bar - start - 1));
    rows.push_back(cells);
  }
  ASSERT_EQ(rows.size(), kParameterFields<double>.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const ParameterField<double>& field = kParameterFields<double>[k];
    ASSERT_GE(rows[k].size(), 6u) << k;
    EXPECT_EQ(rows[k][0], field.name);
    EXPECT_EQ(rows[k][1], field.unit) << field.name;
    EXPECT_EQ(rows[k][4].substr(0, field.physical.describe().size()), field.physical.describe()) << field.name;
    EXPECT_EQ(rows[k][5], "[" + format_number(field.fit_low) + ", " + format_number(field.fit_high) + "]")
        << field.name;
    // The fit searches only where the model is valid.
    EXPECT_TRUE(field.physical.contains(field.fit_low) && field.physical.contains(field.fit_high)) << field.name;
  }
}

TEST(ParameterTable, ValidationNamesTheRangeOfTheTable) {
  Parameters<double> par = testing::toyoura<double>();
  par.nu = 0.5;
  try {
    validate_parameters(par);
    FAIL() << "nu = 0.5 accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'nu' = 0.5 is not physical: it must be in (-1, 0.5)"),
              std::string::npos) << e.what();
  }
  // A cone narrower than the integration can resolve in bounded work (acst_model.h): the message
  // writes the value as it is (to_string wrote 1e-8 as 0.000000).
  par = testing::toyoura<double>();
  par.m = 1e-8;
  try {
    validate_parameters(par);
    FAIL() << "m = 1e-8 accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'m' = 1e-08 is not physical: it must be >= 0.0001"),
              std::string::npos) << e.what();
  }
  par.m = 1e-4;  // the closed end
  EXPECT_NO_THROW(validate_parameters(par));
  par = testing::toyoura<double>();
  par.m = par.c * par.M_c + 0.1;  // inside (0, inf) but outside the critical cone
  EXPECT_THROW(validate_parameters(par), std::runtime_error);
  par = testing::toyoura<double>();
  par.c = 1.0;  // the closed end of (0, 1]
  EXPECT_NO_THROW(validate_parameters(par));
}

// A set filled in member by member (as the FE tests and the UMAT do) that misses one is refused by
// the missing one's name: every member starts unset (NaN).
TEST(ParameterTable, AParameterLeftUnsetIsNamed) {
  const Parameters<double> full = testing::toyoura<double>();
  for (const ParameterField<double>& missing : kParameterFields<double>) {
    Parameters<double> par;
    for (const ParameterField<double>& field : kParameterFields<double>)
      if (&field != &missing) par.*field.member = full.*field.member;
    try {
      validate_parameters(par);
      ADD_FAILURE() << missing.name << " left unset was accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("'") + missing.name + "' = nan"),
                std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace model::acst
