// The parameter file: round trip and errors that name the key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "calibration/acst_model.h"
#include "toyoura.h"

namespace calibration {
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

// The error message of read_parameters_json, or "" when it does not throw.
std::string read_error(const std::string& text) {
  const std::string path = temp_path("bad");
  write_text(path, text);
  try {
    read_parameters_json(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
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

}  // namespace
}  // namespace calibration
