#include "shards.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "csv_table.hpp"
#include "dtlab/experiments/experiment.hpp"
#include "machine_record.hpp"
#include "run_columns.hpp"
#include "study_output.hpp"

namespace dtlab::experiments {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// What shapes the plan and its rows, beside the keys: machine-specific paths (the data folder,
// the TetGen program) are left out, so that shards on other machines still match.
json parameters_json(const StudyParams& p) {
  json j;
  j["quick"] = p.quick;
  j["seeds"] = p.seeds;
  j["threads"] = p.threads;
  j["sizes"] = p.sizes;
  j["inputs"] = p.inputs;
  std::vector<std::string> locations;
  for (const engine::Location l : p.locations) locations.emplace_back(engine::to_string(l));
  j["locations"] = locations;
  j["distribution"] = engine::to_string(p.distribution);
  j["timeout_seconds"] = p.timeout_seconds;
  j["tools"] = p.tools;
  return j;
}

struct ShardDir {
  fs::path dir;
  json plan;
  json machine;
  Shard shard;
};

json read_json(const fs::path& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) {
    throw std::invalid_argument(path.parent_path().string() + ": no " + path.filename().string() +
                                " (" + what + ")");
  }
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw std::invalid_argument(path.string() + ": not JSON: " + e.what());
  }
}

ShardDir read_shard(const fs::path& dir) {
  ShardDir s;
  s.dir = dir;
  s.plan = read_json(dir / "plan.json", "not the folder of a dtlab experiment run");
  s.machine = read_json(dir / "machine.json", "its machine record");
  const json& shard = s.plan.at("shard");
  if (shard.is_null()) {
    throw std::invalid_argument(dir.string() + " is a whole study, not a shard (--shard K/N)");
  }
  s.shard.index = shard.at("index").get<int>();
  s.shard.count = shard.at("count").get<int>();
  return s;
}

std::string shard_name(const Shard& s) {
  return std::to_string(s.index) + "/" + std::to_string(s.count);
}

// The shards must be of one study, one commit, one plan with the same parameters, and N of them.
void check_same_study(const std::vector<ShardDir>& shards) {
  const ShardDir& first = shards.front();
  for (const ShardDir& s : shards) {
    for (const char* field : {"study", "commit", "parameters", "plan", "groups"}) {
      const json& mine = s.plan.at(field);
      const json& theirs = first.plan.at(field);
      if (mine == theirs) continue;
      std::string detail;
      if (mine.is_string())
        detail = " (" + mine.get<std::string>() + " against " + theirs.get<std::string>() + ")";
      if (mine.is_object()) {
        for (const auto& [key, value] : mine.items()) {
          if (!theirs.contains(key) || theirs.at(key) != value) {
            detail += (detail.empty() ? " (" : ", ") + key + ": " + value.dump() + " against " +
                      (theirs.contains(key) ? theirs.at(key).dump() : "none");
          }
        }
        if (!detail.empty()) detail += ")";
      }
      throw std::invalid_argument(
          s.dir.string() + " (shard " + shard_name(s.shard) + ") is foreign: field \"" + field +
          "\" of its plan.json differs from " + first.dir.string() + "'s" + detail);
    }
    if (s.shard.count != first.shard.count) {
      throw std::invalid_argument(s.dir.string() + " is shard " + shard_name(s.shard) + ", " +
                                  first.dir.string() + " shard " + shard_name(first.shard) +
                                  ": one study is cut into one number of shards");
    }
  }
  std::map<int, const ShardDir*> by_index;
  for (const ShardDir& s : shards) {
    const auto [it, fresh] = by_index.emplace(s.shard.index, &s);
    if (!fresh) {
      throw std::invalid_argument("shard " + shard_name(s.shard) + " given twice: " +
                                  it->second->dir.string() + " and " + s.dir.string());
    }
  }
  std::string missing;
  for (int k = 1; k <= first.shard.count; ++k) {
    if (by_index.count(k) == 0) missing += (missing.empty() ? "" : ", ") + std::to_string(k);
  }
  if (!missing.empty()) {
    throw std::invalid_argument("shards missing: " + missing + " of " +
                                std::to_string(first.shard.count));
  }
}

}  // namespace

Shard parse_shard(const std::string& text) {
  if (text.empty()) return {};
  Shard s;
  int used = 0;
  if (std::sscanf(text.c_str(), "%d/%d%n", &s.index, &s.count, &used) != 2 ||
      used != static_cast<int>(text.size()) || s.count < 1 || s.count > 100000 || s.index < 1 ||
      s.index > s.count) {
    throw std::invalid_argument("--shard " + text + ": K/N with 1 <= K <= N <= 100000");
  }
  return s;
}

std::string plan_json(const std::string& study, const Shard& shard, const std::string& commit,
                      const StudyParams& params, const std::vector<std::string>& plan_keys,
                      const std::vector<int>& groups) {
  json j;
  j["study"] = study;
  j["shard"] =
      shard.count == 0 ? json(nullptr) : json{{"index", shard.index}, {"count", shard.count}};
  j["commit"] = commit;
  j["parameters"] = parameters_json(params);
  j["plan"] = plan_keys;
  j["groups"] = groups;
  return j.dump(1);
}

int merge_experiment(const std::vector<std::string>& dirs, const ExperimentOptions& options) {
  if (options.out_dir.empty() || dirs.empty()) {
    std::fprintf(stderr, "dtlab: error: dtlab experiment merge OUT DIR... (at least one DIR)\n");
    return 2;
  }
  std::error_code ignored;
  for (const std::string& d : dirs) {
    if (fs::equivalent(options.out_dir, d, ignored)) {
      throw std::invalid_argument("OUT " + options.out_dir +
                                  " is one of the shards' folders: "
                                  "merge into another folder");
    }
  }
  std::vector<ShardDir> shards;
  for (const std::string& d : dirs) shards.push_back(read_shard(d));
  check_same_study(shards);
  const std::string name = shards.front().plan.at("study").get<std::string>();
  const Study* study = find_study(name);
  if (study == nullptr) throw std::invalid_argument("the shards are of an unknown study " + name);
  std::sort(shards.begin(), shards.end(),
            [](const ShardDir& a, const ShardDir& b) { return a.shard.index < b.shard.index; });

  // Every planned run exactly once, from the shard whose slice it is.
  const std::vector<std::string> plan =
      shards.front().plan.at("plan").get<std::vector<std::string>>();
  const std::vector<int> groups = shards.front().plan.at("groups").get<std::vector<int>>();
  const std::string commit = shards.front().plan.at("commit").get<std::string>();
  if (groups.size() != plan.size())
    throw std::invalid_argument("plan.json: groups and plan differ in length");
  std::map<std::string, std::size_t> position;
  for (std::size_t i = 0; i < plan.size(); ++i) position[plan[i]] = i;
  std::vector<std::vector<std::string>> rows(plan.size());
  std::vector<std::string> from(plan.size());
  const std::size_t key_column = run_column("run_key");
  for (const ShardDir& s : shards) {
    const fs::path csv = s.dir / (name + ".csv");
    if (!fs::exists(csv)) throw std::invalid_argument(s.dir.string() + ": no " + name + ".csv");
    const CsvTable table = read_csv(csv.string());
    if (table.header != run_columns()) {
      throw std::invalid_argument(csv.string() +
                                  ": its columns are not this version's (merge with the dtlab "
                                  "that ran the shards)");
    }
    for (const auto& row : table.rows) {
      const std::string& key = row[key_column];
      const auto it = position.find(key);
      if (it == position.end()) {
        throw std::invalid_argument(csv.string() + ": run " + key + " is not in the plan");
      }
      if (groups[it->second] % s.shard.count != s.shard.index - 1) {
        throw std::invalid_argument(csv.string() + ": run " + key + " belongs to another shard");
      }
      if (!rows[it->second].empty()) {
        throw std::invalid_argument(csv.string() + ": run " + key + " twice");
      }
      if (table.get(row, "commit") != commit) {
        throw std::invalid_argument(csv.string() + ": run " + key + " was measured at commit " +
                                    table.get(row, "commit") + ", the shards' plan at " + commit +
                                    ": run that shard again without --resume");
      }
      rows[it->second] = row;
      from[it->second] = s.dir.string();
    }
  }
  std::size_t missing = 0;
  std::string example;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (!rows[i].empty()) continue;
    if (missing++ == 0) {
      const ShardDir& owner = shards[static_cast<std::size_t>(groups[i]) % shards.size()];
      example = plan[i] + " (shard " + shard_name(owner.shard) + ", " + owner.dir.string() + ")";
    }
  }
  if (missing > 0) {
    throw std::invalid_argument(std::to_string(missing) + " of the plan's " +
                                std::to_string(plan.size()) + " runs are missing, e.g. " + example +
                                ": run that shard again with --resume");
  }

  const fs::path out(options.out_dir);
  fs::create_directories(out);
  { CsvAppender merged((out / (name + ".csv")).string(), run_columns(), rows); }
  json machines = json::array();
  std::vector<std::pair<std::string, std::string>> machine_shards;  // machine line, its shards
  for (const ShardDir& s : shards) {
    json record = s.machine;
    record["shard"] = shard_name(s.shard);
    record["folder"] = s.dir.string();
    machines.push_back(record);
    const std::string line = machine_line(s.machine);
    auto it = std::find_if(machine_shards.begin(), machine_shards.end(),
                           [&](const auto& m) { return m.first == line; });
    if (it == machine_shards.end()) it = machine_shards.insert(it, {line, ""});
    it->second += (it->second.empty() ? "" : ", ") + shard_name(s.shard);
  }
  std::string machine_lines;
  for (const auto& [line, names] : machine_shards) {
    machine_lines += "Machine of shards " + names + ": " + line + ". ";
  }
  write_text(out / "machines.json", machines.dump(2) + "\n");
  write_text(out / "machine.json", machine_json(source_tree(), options.command_line) + "\n");
  json merged_plan = shards.front().plan;
  merged_plan["shard"] = nullptr;
  merged_plan["merged_from"] = dirs;
  write_text(out / "plan.json", merged_plan.dump(1) + "\n");

  SummaryHeader header;
  // Appended piece by piece: "`" + std::string trips GCC 12's false -Wrestrict (bug 105329).
  header.command = "`";
  header.command += shards.front().machine.value("command", std::string("?"));
  header.command += "`, as " + std::to_string(shards.size()) + " shards merged by `";
  header.command += options.command_line + "`";
  header.machines = machine_lines.substr(0, machine_lines.size() - 1);
  header.seeds = shards.front().plan.at("parameters").at("seeds").get<int>();
  std::fprintf(stderr, "dtlab: merged %zu shards (%zu runs) into %s\n", shards.size(), plan.size(),
               out.c_str());
  return write_summary(*study, out, header, options) ? 0 : 2;
}

}  // namespace dtlab::experiments
