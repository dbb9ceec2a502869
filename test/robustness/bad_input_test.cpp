// Runs `cohort info` and `cohort render` on every entry of the malformed-input corpus
// (test/data/bad-input/expected.json, written by make-corpus.py there) and checks what a user sees:
// the exit code, a message naming the file, no crash or sanitizer report, no hang (each run has a
// time limit), no output or temporary file left by a failed run, and for legal-but-odd scenes the
// warning and a correct image.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <ostream>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "runtime/image/image.h"

namespace fs = std::filesystem;

namespace {

const fs::path kCorpus = fs::path(COHORT_SOURCE_DIR) / "test" / "data" / "bad-input";
// Generous: the slowest entry takes well under a second; a cold kernel compile takes longer.
constexpr int kInfoSeconds = 60;
constexpr int kRenderSeconds = 180;

struct Entry {
  std::string file;
  int exit = 0;
  std::string message;  // exit 2
  std::string warning;  // exit 0
  std::string image;    // "", "black" or "same_as"
  std::string same_as;
  std::string create;   // "", "directory", "unreadable", "missing"
};

// What gtest shows for a parameter (in test names and failures): the file.
void PrintTo(const Entry& e, std::ostream* os) { *os << e.file; }

std::vector<Entry> load_manifest() {
  std::ifstream in(kCorpus / "expected.json");
  if (!in) return {};
  const auto j = nlohmann::json::parse(in);
  std::vector<Entry> entries;
  for (const auto& e : j.at("entries")) {
    Entry entry{.file = e.at("file"), .exit = e.at("exit"), .message = e.value("message", ""),
                .warning = e.value("warning", ""), .create = e.value("create", "")};
    if (e.contains("image")) {
      if (e["image"].is_string()) {
        entry.image = e["image"];
      } else {
        entry.image = "same_as";
        entry.same_as = e["image"].at("same_as");
      }
    }
    entries.push_back(entry);
  }
  return entries;
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct Outcome {
  int code = -1;         // exit status; 128 + N for signal N (as the shell reports it)
  std::string output;    // stdout and stderr
  std::string command;
};

Outcome run(const std::string& prefix, int seconds, const std::string& args) {
  Outcome r;
  r.command = fmt::format("{}timeout -k 10 {} {} {} 2>&1", prefix, seconds, quote(COHORT_BINARY), args);
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(r.command.c_str(), "r"), pclose);
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe.get())) > 0) r.output.append(buf.data(), n);
  const int status = pclose(pipe.release());
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  return r;
}

class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    path_ = fs::temp_directory_path() /
            fmt::format("cohort-robust-{}-{}-{}", tag, ::getpid(), std::random_device{}());
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    // an unreadable or foreign-owned entry must not stop the clean-up
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A crash, a hang or a sanitizer report fails the entry whatever its exit code.
void expect_clean_exit(const Outcome& r) {
  EXPECT_NE(r.code, 124) << "timed out: " << r.command;
  EXPECT_FALSE(r.code >= 125) << "killed by signal " << r.code - 128 << ": " << r.command << "\n" << r.output;
  for (const char* report : {"Sanitizer", "runtime error:", "terminate called", "Segmentation fault"})
    EXPECT_FALSE(contains(r.output, report)) << r.command << "\n" << r.output;
}

void expect_outcome(const Entry& e, const Outcome& r) {
  expect_clean_exit(r);
  EXPECT_EQ(r.code, e.exit) << r.command << "\n" << r.output;
  if (e.exit == 2) {
    EXPECT_TRUE(contains(r.output, "cohort: ")) << r.output;
    EXPECT_TRUE(contains(r.output, e.file)) << "the message does not name the file:\n" << r.output;
    EXPECT_TRUE(contains(r.output, e.message)) << "expected '" << e.message << "' in:\n" << r.output;
  } else {
    EXPECT_TRUE(contains(r.output, e.warning)) << "expected warning '" << e.warning << "' in:\n" << r.output;
  }
}

// Renders `scene` into `out`/x at 16x16, 1 spp; returns the run.
Outcome render(const std::string& prefix, const fs::path& scene, const TempDir& out) {
  return run(prefix, kRenderSeconds,
             fmt::format("render {} --res 16x16 --spp 1 -o {} --stats {}", quote(scene.string()),
                         quote((out / "x").string()), quote((out / "stats.json").string())));
}

class BadInput : public ::testing::TestWithParam<Entry> {};

TEST_P(BadInput, InfoAndRender) {
  const Entry& e = GetParam();
  TempDir work("in");
  TempDir home("home");  // for the unreadable entry: HOME of the user the commands run as
  std::string prefix;  // runs the commands as another user where root would read an unreadable file
  fs::path scene = kCorpus / e.file;
  if (!e.create.empty()) {
    scene = work / e.file;
    if (e.create == "directory") {
      fs::create_directories(scene);
    } else if (e.create == "unreadable") {
      std::ofstream(scene) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
      fs::permissions(scene, fs::perms::none);
      if (::access(scene.c_str(), R_OK) == 0) {
        // root reads anything: drop to nobody (with a writable HOME for PoCL's cache) if we can
        if (::geteuid() != 0 || std::system("command -v setpriv >/dev/null 2>&1") != 0)
          GTEST_SKIP() << "cannot make an unreadable file as this user";
        fs::permissions(work.path(), fs::perms::all);
        fs::permissions(home.path(), fs::perms::all);
        prefix = fmt::format("HOME={0} XDG_CACHE_HOME={0} setpriv --reuid=65534 --regid=65534 --clear-groups ",
                             quote(home.path().string()));
      }
    } else {
      ASSERT_EQ(e.create, "missing");
    }
  }
  const std::set<std::string> corpus_before = listing(kCorpus);
  const std::set<std::string> work_before = listing(work.path());

  {
    SCOPED_TRACE("cohort info");
    expect_outcome(e, run(prefix, kInfoSeconds, "info " + quote(scene.string())));
  }

  TempDir out("out");
  if (!prefix.empty()) fs::permissions(out.path(), fs::perms::all);
  {
    SCOPED_TRACE("cohort render");
    expect_outcome(e, render(prefix, scene, out));
  }
  if (e.exit != 0) {
    EXPECT_TRUE(listing(out.path()).empty()) << "a failed render left files behind";
  } else {
    EXPECT_EQ(listing(out.path()), (std::set<std::string>{"x.exr", "x.png", "stats.json"}))
        << "only the outputs, no temporary file";
    std::ifstream stats_in(out / "stats.json");
    const auto stats = nlohmann::json::parse(stats_in);
    EXPECT_EQ(stats["image"]["width"], 16);
    EXPECT_EQ(stats["image"]["height"], 16);
    const cohort::Image image = cohort::read_exr(out / "x.exr");
    ASSERT_EQ(image.rgb.size(), 16u * 16u * 3u);
    for (float v : image.rgb) ASSERT_TRUE(std::isfinite(v)) << "non-finite pixel";
    if (e.image == "black") {
      EXPECT_EQ(stats["scene_stats"]["emitters"], 0);
      EXPECT_TRUE(std::all_of(image.rgb.begin(), image.rgb.end(), [](float v) { return v == 0.f; }))
          << "a scene without light must render black";
    } else if (e.image == "same_as") {
      // The reference is lit (a black image would prove nothing) and renders the same bits.
      TempDir ref("ref");
      const Outcome rr = render("", kCorpus / e.same_as, ref);
      ASSERT_EQ(rr.code, 0) << rr.output;
      const cohort::Image expected = cohort::read_exr(ref / "x.exr");
      EXPECT_TRUE(std::any_of(expected.rgb.begin(), expected.rgb.end(), [](float v) { return v > 0.f; }))
          << e.same_as << " renders black";
      EXPECT_EQ(image.rgb, expected.rgb) << "differs from " << e.same_as;
    }
  }
  EXPECT_EQ(listing(kCorpus), corpus_before) << "the corpus directory changed";
  EXPECT_EQ(listing(work.path()), work_before) << "files left next to the input";
}

std::string entry_name(const ::testing::TestParamInfo<Entry>& info) {
  std::string name = info.param.file;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInput, ::testing::ValuesIn(load_manifest()), entry_name);

TEST(BadInputCorpus, ManifestCoversEveryScene) {
  const std::vector<Entry> entries = load_manifest();
  ASSERT_GE(entries.size(), 40u) << "expected.json is missing or short";
  std::set<std::string> named;
  for (const Entry& e : entries) {
    EXPECT_TRUE(named.insert(e.file).second) << "listed twice: " << e.file;
    if (!e.same_as.empty()) named.insert(e.same_as);
    EXPECT_TRUE(e.exit == 0 || e.exit == 2) << e.file;
    if (e.exit == 0) {
      EXPECT_FALSE(e.warning.empty()) << e.file << ": a legal-but-odd scene must warn";
      EXPECT_FALSE(e.image.empty()) << e.file << ": and say what its image is";
    }
    if (e.create.empty()) {
      EXPECT_TRUE(fs::is_regular_file(kCorpus / e.file)) << e.file;
      EXPECT_LT(fs::file_size(kCorpus / e.file), 100u * 1024u) << e.file;
    }
  }
  // Every stored file is an entry, a reference of one, or a file an entry refers to (.mtl, .png).
  for (const std::string& name : listing(kCorpus)) {
    const fs::path ext = fs::path(name).extension();
    if (name == "expected.json" || name == "make-corpus.py" || ext == ".mtl" || ext == ".png") continue;
    EXPECT_TRUE(named.count(name)) << name << " is not in expected.json";
  }
}

}  // namespace
