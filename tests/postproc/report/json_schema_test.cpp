// Both JSON documents (the report's and `post --summary-json`'s) against
// the one schema in docs/vcpost.schema.json, with a small validator of the
// JSON Schema keywords that file uses; and every key of the schema listed
// in docs/json.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "tests/postproc/cli_run_support.h"
#include "tests/postproc/temp_folder.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kSource = VCPOST_SOURCE_DIR;

// The subset of JSON Schema (2020-12) docs/vcpost.schema.json is written
// in: $ref (local), type, const, enum, minimum, maximum, required,
// properties, additionalProperties: false, items, allOf, oneOf. Collects
// one message per violation with the JSON pointer of the instance.
class SchemaValidator {
 public:
  explicit SchemaValidator(json root) : root_(std::move(root)) {}

  std::vector<std::string> validate(const json& instance) const {
    std::vector<std::string> errors;
    check(root_, instance, "", errors);
    return errors;
  }

 private:
  static bool has_type(const json& v, const std::string& type) {
    if (type == "object") return v.is_object();
    if (type == "array") return v.is_array();
    if (type == "string") return v.is_string();
    if (type == "number") return v.is_number();
    if (type == "integer") return v.is_number_integer();
    if (type == "boolean") return v.is_boolean();
    if (type == "null") return v.is_null();
    ADD_FAILURE() << "schema names an unknown type " << type;
    return false;
  }

  const json& resolve(const std::string& ref) const {
    const std::string prefix = "#/$defs/";
    if (ref.rfind(prefix, 0) != 0) ADD_FAILURE() << "unsupported $ref " << ref;
    return root_.at("$defs").at(ref.substr(prefix.size()));
  }

  void check(const json& schema, const json& v, const std::string& at,
             std::vector<std::string>& errors) const {
    static const std::set<std::string> known = {"$schema",    "$id",
                                                "title",      "description",
                                                "$defs",      "$ref",
                                                "type",       "const",
                                                "enum",       "minimum",
                                                "maximum",    "required",
                                                "properties", "additionalProperties",
                                                "items",      "allOf",
                                                "oneOf"};
    for (const auto& [key, value] : schema.items()) {
      if (!known.count(key)) ADD_FAILURE() << "validator does not know keyword " << key;
    }
    if (schema.contains("$ref")) check(resolve(schema["$ref"]), v, at, errors);
    if (schema.contains("type")) {
      const json& t = schema["type"];
      bool ok = false;
      for (const json& one : t.is_array() ? t : json::array({t})) ok = ok || has_type(v, one);
      if (!ok) {
        errors.push_back(at + ": " + v.type_name() + " where the schema wants " + t.dump());
        return;
      }
    }
    if (schema.contains("const") && v != schema["const"]) {
      errors.push_back(at + ": " + v.dump() + " is not " + schema["const"].dump());
    }
    if (schema.contains("enum") &&
        std::find(schema["enum"].begin(), schema["enum"].end(), v) == schema["enum"].end()) {
      errors.push_back(at + ": " + v.dump() + " is not one of " + schema["enum"].dump());
    }
    if (v.is_number()) {
      if (schema.contains("minimum") && v.get<double>() < schema["minimum"].get<double>()) {
        errors.push_back(at + ": " + v.dump() + " below the minimum");
      }
      if (schema.contains("maximum") && v.get<double>() > schema["maximum"].get<double>()) {
        errors.push_back(at + ": " + v.dump() + " above the maximum");
      }
    }
    if (v.is_object()) {
      for (const json& key : schema.value("required", json::array())) {
        if (!v.contains(key.get<std::string>())) errors.push_back(at + ": no key " + key.dump());
      }
      const json properties = schema.value("properties", json::object());
      for (const auto& [key, value] : v.items()) {
        if (properties.contains(key)) {
          check(properties[key], value, at + "/" + key, errors);
        } else if (schema.value("additionalProperties", true) == false) {
          errors.push_back(at + ": key \"" + key + "\" is not in the schema");
        }
      }
    }
    if (v.is_array() && schema.contains("items")) {
      for (std::size_t i = 0; i < v.size(); ++i) {
        check(schema["items"], v[i], at + "/" + std::to_string(i), errors);
      }
    }
    for (const json& part : schema.value("allOf", json::array())) check(part, v, at, errors);
    if (schema.contains("oneOf")) {
      int matches = 0;
      std::vector<std::string> all;
      for (const json& part : schema["oneOf"]) {
        std::vector<std::string> e;
        check(part, v, at, e);
        if (e.empty()) ++matches;
        all.insert(all.end(), e.begin(), e.end());
      }
      if (matches != 1) {
        errors.push_back(at + ": matches " + std::to_string(matches) + " of oneOf");
        if (matches == 0) errors.insert(errors.end(), all.begin(), all.end());
      }
    }
  }

  json root_;
};

json read_json(const fs::path& path) { return json::parse(vcpost::testing::slurp(path)); }

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& line : lines) out += line + "\n";
  return out;
}

class JsonSchema : public ::testing::Test {
 protected:
  // `report` of a sample with its job summary: {report, summary}.
  std::pair<json, json> documents(const std::string& job) {
    const auto run = vcpost::testing::run_vcpost(
        "report " + job + " -q -o r.json --summary-json s.json", dir_.path());
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return {read_json(dir_ / "r.json"), read_json(dir_ / "s.json")};
  }

  const SchemaValidator validator_{read_json(kSource / "docs/vcpost.schema.json")};
  vcpost::testing::Folder dir_;
};

const std::string kWavy = "'" + (kSource / "samples/wavy_raster_a0_ae2.nc").string() +
                          "' --model '" + (kSource / "samples/wavy.step").string() +
                          "' --tool ball:10 --vc 120 --ap 0.3 --machine mazak-3axis";

TEST_F(JsonSchema, BothDocumentsFollowTheSchema) {
  const auto [report, summary] = documents(kWavy);
  EXPECT_EQ(report["schema"], "vcpost-report/2");
  EXPECT_EQ(summary["schema"], "vcpost-summary/2");
  EXPECT_EQ(joined(validator_.validate(report)), "");
  EXPECT_EQ(joined(validator_.validate(summary)), "");
  // The same quantities under the same keys, with the same values where
  // both documents take them from the job.
  for (const char* key : {"inputs", "profile", "vc_nominal", "blocks", "time_s", "words_written",
                          "s_placement", "sections", "tool_notes"}) {
    EXPECT_EQ(report[key], summary[key]) << key;
  }
  for (const char* key : {"total", "touching", "lifted", "missed", "gouging", "ae_measured",
                          "ae_given", "ae_first_pass"}) {
    EXPECT_EQ(report["points"][key], summary["points"][key]) << key;
  }
}

TEST_F(JsonSchema, TheValidatorRefusesADocumentOffTheSchema) {
  const auto [report, summary] = documents(kWavy);
  json renamed = summary;
  renamed["points"]["gouge"] = renamed["points"]["gouging"];
  renamed["points"].erase("gouging");
  const auto errors = validator_.validate(renamed);
  EXPECT_NE(joined(errors).find("/points: no key \"gouging\""), std::string::npos)
      << joined(errors);
  EXPECT_NE(joined(errors).find("key \"gouge\" is not in the schema"), std::string::npos);

  json wrong_type = report;
  wrong_type["before"]["within_10_percent"] = "most";
  EXPECT_NE(joined(validator_.validate(wrong_type)).find("/before/within_10_percent: string"),
            std::string::npos);
  json out_of_range = report;
  out_of_range["after"]["within_5_percent"] = 1.5;
  EXPECT_NE(joined(validator_.validate(out_of_range)).find("above the maximum"), std::string::npos);
  json old_version = report;
  old_version["schema"] = "vcpost-report/1";
  EXPECT_FALSE(validator_.validate(old_version).empty());
}

TEST_F(JsonSchema, EveryKeyOfTheSchemaIsDocumented) {
  const json schema = read_json(kSource / "docs/vcpost.schema.json");
  const std::string docs = vcpost::testing::slurp(kSource / "docs/json.md");
  std::set<std::string> keys;
  std::function<void(const json&)> collect = [&](const json& node) {
    if (node.is_object()) {
      if (node.contains("properties") && node["properties"].is_object()) {
        for (const auto& [key, value] : node["properties"].items()) keys.insert(key);
      }
      for (const auto& [key, value] : node.items()) collect(value);
    } else if (node.is_array()) {
      for (const json& item : node) collect(item);
    }
  };
  collect(schema);
  EXPECT_GT(keys.size(), 60u);
  for (const std::string& key : keys) {
    EXPECT_NE(docs.find("`" + key + "`"), std::string::npos) << key << " is not in docs/json.md";
  }
}

}  // namespace
