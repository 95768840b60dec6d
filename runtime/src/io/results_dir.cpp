#include "io/results_dir.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "io/atomic_file.h"
#include "io/durable.h"
#include "nlohmann/json.hpp"
#include "util/error.h"

namespace lrigid {

namespace fs = std::filesystem;
using nlohmann::json;

volatile std::sig_atomic_t g_results_commit_under_way = 0;

namespace {

// What lrigid wrote in a folder: files by name, folders with the files in them.
struct Owned {
  std::set<std::string> files;
  std::map<std::string, std::set<std::string>> folders;
  bool any() const { return !files.empty() || !folders.empty(); }
};

// results folders without a manifest (written by an older lrigid): summary.json from lrigid
// (it has "version" and "outputs"), the result files by their names and the frames by their
// pattern <folder>_NNNNNN.vtp
Owned legacy_owned(const fs::path& d) {
  Owned o;
  std::error_code ec0;
  if (!fs::is_regular_file(fs::symlink_status(d / "summary.json", ec0))) return o;
  std::ifstream in(d / "summary.json");
  if (!in) return o;
  const json s = json::parse(in, nullptr, false);
  if (!s.is_object() || !s.contains("version") || !s.contains("outputs")) return o;
  std::error_code ec;
  for (const char* f : {"summary.json", "trajectories.csv", "bodies.pvd", "shapes.pvd",
                        "animation.glb", "landings.csv"})
    if (fs::is_regular_file(fs::symlink_status(d / f, ec))) o.files.insert(f);
  for (const std::string folder : {"bodies", "shapes"}) {
    if (!fs::is_directory(fs::symlink_status(d / folder, ec))) continue;
    auto& names = o.folders[folder];
    for (const auto& e : fs::directory_iterator(d / folder, ec)) {
      const std::string n = e.path().filename().string();
      const std::string stem = folder + "_";
      if (n.size() == stem.size() + 10 && n.rfind(stem, 0) == 0 &&
          n.compare(n.size() - 4, 4, ".vtp") == 0 &&
          n.find_first_not_of("0123456789", stem.size()) == n.size() - 4 &&
          e.is_regular_file(ec))
        names.insert(n);
    }
  }
  return o;
}

Owned owned_from_json(const json& j) {
  Owned o;
  for (const auto& f : j.at("files")) o.files.insert(f.get<std::string>());
  for (const auto& [folder, files] : j.at("folders").items())
    for (const auto& f : files) o.folders[folder].insert(f.get<std::string>());
  return o;
}

Owned read_owned(const fs::path& d) {
  const fs::path m = d / kManifestName;
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(m, ec))) return legacy_owned(d);
  std::ifstream in(m);
  if (!in) throw Error(ExitCode::Output, where(m.string(), "", "cannot be read"));
  const json j = json::parse(in, nullptr, false);
  try {
    return owned_from_json(j);
  } catch (const json::exception& e) {
    throw Error(ExitCode::Output,
                where(m.string(), "",
                      std::string("not a manifest lrigid can read (") + e.what() +
                          "): lrigid cannot tell which files here it wrote; remove it only if "
                          "nothing in this folder is yours, or write elsewhere with -o"));
  }
}

json manifest_json(const Owned& o) {
  json folders = json::object();
  for (const auto& [name, files] : o.folders) folders[name] = files;
  return {{"written_by", std::string("lrigid ") + LRIGID_VERSION},
          {"about", "the files lrigid wrote in this folder: it replaces or removes only these"},
          {"files", o.files},
          {"folders", folders}};
}


bool exists_nofollow(const fs::path& p) {
  std::error_code ec;
  return fs::exists(fs::symlink_status(p, ec));
}

// the entries of an existing path `name` that lrigid may replace: throws naming what it may not
// touch. Returns the files to remove inside it when it is a folder.
std::vector<std::string> replaceable(const fs::path& d, const std::string& name,
                                     const Owned& owned, bool force) {
  const fs::path p = d / name;
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(p, ec);
  if (!fs::exists(st)) return {};
  const bool dir = fs::is_directory(st);
  const auto of = owned.folders.find(name);
  if (!dir && owned.files.count(name) && fs::is_regular_file(st)) return {};
  if (dir && of != owned.folders.end()) {
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(p, ec)) {
      const std::string n = e.path().filename().string();
      if (!of->second.count(n) || !fs::is_regular_file(e.symlink_status(ec)))
        throw Error(ExitCode::Output,
                    where(e.path().string(), "",
                          "not written by lrigid (not in " + (d / kManifestName).string() +
                              "), in the folder " + name +
                              " that the run replaces: move it away, or write elsewhere with "
                              "-o (--force never removes a folder holding files lrigid did "
                              "not write)"));
      files.push_back(n);
    }
    return files;
  }
  // not lrigid's
  if (force || (dir && !fs::is_empty(p, ec))) {
    if (!dir) return {};
    if (fs::is_empty(p, ec)) return {};
    throw Error(ExitCode::Output,
                where(p.string(), "",
                      "a folder lrigid did not write, holding files, where the run writes its " +
                          std::string("results: move it away, or write elsewhere with -o ") +
                          "(--force replaces files, never a folder with content)"));
  }
  throw Error(ExitCode::Output,
              where(p.string(), "",
                    std::string(dir ? "a folder" : "a file") +
                        " lrigid did not write (not in " + (d / kManifestName).string() +
                        ") is where the run writes its results: move it away, write elsewhere "
                        "with -o, or pass --force to replace it"));
}

bool rename_ok(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  return !ec;
}

[[noreturn]] void rename_failed(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  throw Error(ExitCode::Output, where(to.string(), "",
                                      "cannot move " + from.filename().string() +
                                          " into place: " + ec.message()));
}

// removes the files an earlier result named in a folder, then the folder if empty
void remove_owned(const fs::path& p, bool dir, const std::vector<std::string>& files) {
  std::error_code ec;
  if (!dir) {
    fs::remove(p, ec);
    return;
  }
  for (const std::string& f : files) fs::remove(p / f, ec);
  fs::remove(p, ec);  // only when empty: never what lrigid did not write
  if (exists_nofollow(p))
    std::fprintf(stderr,
                 "lrigid: warning: %s holds files lrigid did not write; left there\n",
                 p.string().c_str());
}

// Carries out a journal: earlier results aside (summary.json first), new ones into place
// (summary.json last), the manifest, the earlier results and the checkpoint removed, the
// journal removed. Idempotent: each step looks at what is there, so a run of it that was
// interrupted at any point is completed by running it again. `undo` (the live commit): a
// failing rename puts everything back and removes the journal.
void roll_forward(const fs::path& d, const json& j, bool live) {
  const fs::path journal = d / kJournalName;
  const json& items = j.at("items");
  const json& aside = j.at("aside");
  std::map<std::string, std::string> tmp_of;  // final name -> temporary
  for (const auto& it : items) tmp_of[it.at("final")] = it.at("tmp");
  std::vector<std::pair<fs::path, fs::path>> done;  // renames made (from, to), for the undo
  auto undo = [&] {
    for (auto it = done.rbegin(); it != done.rend(); ++it) rename_ok(it->second, it->first);
    std::error_code ec;
    fs::remove(journal, ec);
    sync_path(d.string());
  };
  auto move = [&](const fs::path& from, const fs::path& to) {
    if (rename_ok(from, to)) {
      done.emplace_back(from, to);
      return;
    }
    if (!live) rename_failed(from, to);
    std::error_code ec;
    fs::rename(from, to, ec);
    const std::string why = ec.message();
    undo();
    throw Error(ExitCode::Output,
                where(to.string(), "",
                      "cannot move " + from.filename().string() + " there (" + why +
                          "); nothing was changed: the earlier results are as they were and "
                          "the run's output is kept under its temporary names"));
  };
  // 1. the earlier results aside, summary.json first: from then on the folder holds no
  // summary.json, so nothing reads it as a result until every new file is in place
  for (const auto& a : aside) {
    const fs::path fin = d / a.at("final").get<std::string>();
    const fs::path bak = d / a.at("backup").get<std::string>();
    const auto t = tmp_of.find(a.at("final").get<std::string>());
    const bool new_one_placed = t != tmp_of.end() && !exists_nofollow(d / t->second);
    if (exists_nofollow(fin) && !exists_nofollow(bak) && !new_one_placed) move(fin, bak);
  }
  // 2. the new results into place, summary.json last
  for (const auto& it : items) {
    const fs::path tmp = d / it.at("tmp").get<std::string>();
    if (exists_nofollow(tmp)) move(tmp, d / it.at("final").get<std::string>());
  }
  sync_path(d.string());
  // 3. the earlier results and the checkpoint go (the manifest came in with the new results)
  for (const auto& a : aside) {
    const fs::path bak = d / a.at("backup").get<std::string>();
    if (exists_nofollow(bak))
      remove_owned(bak, a.at("dir").get<bool>(), a.at("files").get<std::vector<std::string>>());
  }
  if (j.contains("checkpoint") && !j["checkpoint"].get<std::string>().empty())
    remove_checkpoint_files((d / j["checkpoint"].get<std::string>()).string());
  std::error_code ec;
  fs::remove(journal, ec);
  sync_path(d.string());
}

}  // namespace

void check_may_write(const std::string& dir, const std::vector<ResultItem>& items, bool force) {
  const fs::path d(dir);
  const Owned owned = read_owned(d);
  for (const ResultItem& it : items) replaceable(d, it.name, owned, force);
}

void commit_results(const std::string& dir, const std::vector<ResultItem>& items, bool force,
                    const std::string& checkpoint_dir) {
  const fs::path d(dir);
  complete_interrupted_finish(dir);  // another run's, decided before this one
  // from here on a SIGINT or SIGTERM kills the run without removing its temporaries: the
  // journal about to be written names them
  struct UnderWay {
    UnderWay() { g_results_commit_under_way = 1; }
    ~UnderWay() { g_results_commit_under_way = 0; }
  } under_way;
  const Owned old = read_owned(d);
  // what is replaced: each name written again, and every earlier result not written again
  // (a folder holds one run's results, not a mixture)
  std::vector<std::string> names;
  for (const ResultItem& it : items) names.push_back(it.name);
  for (const std::string& f : old.files)
    if (std::find(names.begin(), names.end(), f) == names.end()) names.push_back(f);
  for (const auto& [f, files] : old.folders)
    if (std::find(names.begin(), names.end(), f) == names.end()) names.push_back(f);
  // summary.json first: it goes aside before anything else
  std::stable_partition(names.begin(), names.end(),
                        [](const std::string& n) { return n == "summary.json"; });
  const std::string old_tag = ".old" + std::to_string(::getpid());
  json aside = json::array();
  for (const std::string& n : names) {
    const fs::path p = d / n;
    if (!exists_nofollow(p)) continue;
    const std::vector<std::string> files =
        n == kManifestName ? std::vector<std::string>{} : replaceable(d, n, old, force);
    std::error_code ec;
    aside.push_back({{"final", n},
                     {"backup", n + old_tag},
                     {"dir", fs::is_directory(fs::symlink_status(p, ec))},
                     {"files", files}});
  }
  // the new manifest, and every temporary durable before the journal decides the finish
  Owned now;
  json jitems = json::array();
  for (const ResultItem& it : items) {
    const fs::path tmp = d / it.tmp;
    if (it.is_dir) {
      auto& files = now.folders[it.name];
      std::error_code ec;
      for (const auto& e : fs::directory_iterator(tmp, ec)) {
        files.insert(e.path().filename().string());
        sync_path(e.path().string());
      }
      if (ec) throw Error(ExitCode::Output, where(tmp.string(), "", "cannot list: " + ec.message()));
    } else {
      now.files.insert(it.name);
    }
    sync_path(tmp.string());
    jitems.push_back({{"tmp", it.tmp}, {"final", it.name}, {"dir", it.is_dir}});
  }
  // the manifest, written before the journal like every other file, comes in before
  // summary.json: after the decision nothing is written, only renamed and removed
  const std::string manifest_tmp = std::string(kManifestName) + ".tmp" + std::to_string(::getpid());
  write_file_atomically((d / manifest_tmp).string(),
                        [&](std::ostream& o) { o << manifest_json(now).dump(1) << '\n'; });
  {
    json last = jitems.back();  // summary.json
    jitems.back() = {{"tmp", manifest_tmp}, {"final", kManifestName}, {"dir", false}};
    jitems.push_back(last);
    if (exists_nofollow(d / kManifestName)) {
      aside.push_back({{"final", kManifestName},
                       {"backup", std::string(kManifestName) + old_tag},
                       {"dir", false},
                       {"files", json::array()}});
    }
  }
  sync_path(d.string());
  const json journal = {{"about", "lrigid: a finish under way; the next lrigid that opens this "
                                  "folder completes it"},
                        {"items", jitems},
                        {"aside", aside},
                        {"manifest", manifest_json(now)},
                        {"checkpoint", checkpoint_dir}};
  write_file_atomically((d / kJournalName).string(),
                        [&](std::ostream& o) { o << journal.dump(1) << '\n'; });
  roll_forward(d, journal, true);
}

bool complete_interrupted_finish(const std::string& dir) {
  const fs::path d(dir);
  const fs::path journal = d / kJournalName;
  if (!exists_nofollow(journal)) return false;
  std::ifstream in(journal);
  const json j = json::parse(in, nullptr, false);
  try {
    if (!j.is_object())
      throw Error(ExitCode::Output,
                  where(journal.string(), "",
                        "the journal of an interrupted finish is not valid JSON; the results it "
                        "names may be half in place"));
    roll_forward(d, j, false);
  } catch (const json::exception& e) {
    throw Error(ExitCode::Output,
                where(journal.string(), "",
                      std::string("the journal of an interrupted finish is unreadable (") +
                          e.what() + "); the results it names may be half in place"));
  }
  std::fprintf(stderr,
               "lrigid: %s: completed the finish of an earlier run that was interrupted while "
               "moving its results into place (%s); its results are now complete\n",
               dir.c_str(), kJournalName);
  return true;
}

void remove_checkpoint_files(const std::string& checkpoint_dir) {
  std::error_code ec;
  if (!fs::is_directory(checkpoint_dir, ec)) return;
  // latest.json first: without it the folder is no checkpoint
  fs::remove(fs::path(checkpoint_dir) / "latest.json", ec);
  std::vector<fs::path> ours;
  for (const auto& e : fs::directory_iterator(checkpoint_dir, ec)) {
    const std::string n = e.path().filename().string();
    if ((n.rfind("rank", 0) == 0 && n.find(".step") != std::string::npos &&
         n.find(".bin") != std::string::npos) ||
        n.rfind("latest.json.tmp", 0) == 0)
      ours.push_back(e.path());
  }
  for (const fs::path& p : ours) fs::remove(p, ec);
  fs::remove(checkpoint_dir, ec);  // only when empty
}

}  // namespace lrigid
