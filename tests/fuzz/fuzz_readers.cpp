// fuzz_readers: runs the reading tools on mutants of small valid files and reports every run that ends
// in a signal, a hang or an exit code other than 0, 1 and 2.
//
//   fuzz_readers --spec SPEC --mutants N [--seed S] [--timeout SECONDS] [--memory MB] [--jobs J] [--work DIR]
//
// SPEC has one line per reading command: `FILE COMMAND...`, where `{}` in COMMAND stands for the mutant's
// path and a lone `<{}` feeds the mutant on standard input. Each of the N mutants of every file of the
// spec (byte changes, bit flips, truncations, overwritten fields, zeroed or copied blocks, one to three of
// them, drawn from a generator seeded by S and the mutant's number) runs through every command of its
// file, in the folder DIR, with standard output and error discarded, under RLIMIT_AS = MB (0: none) and
// killed after SECONDS. A failing mutant is kept as DIR/failures/NAME-K with the command in NAME-K.txt.
// Exit status: 0 when no run failed, 1 otherwise, 2 on bad usage.
#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

struct Command {
  std::string file;               // the valid file the mutants derive from
  std::vector<std::string> argv;  // with "{}" placeholders
  bool stdin_mutant = false;      // "<{}": the mutant on standard input
  // The tool, and its subcommand if it has one ("mesh-gen check").
  std::string name() const {
    const bool sub = argv.size() > 1 && !argv[1].empty() &&
                     argv[1].find_first_not_of("abcdefghijklmnopqrstuvwxyz") == std::string::npos;
    return std::filesystem::path(argv[0]).filename().string() + (sub ? " " + argv[1] : "");
  }
};

struct Options {
  std::string spec, work = "fuzz-work";
  long mutants = 100;
  std::uint64_t seed = 1;
  double timeout = 20;
  long memory_mb = 4096;
  int jobs = 2;
};

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "fuzz_readers: error: " << why
            << "\nusage: fuzz_readers --spec SPEC --mutants N [--seed S] [--timeout SECONDS] [--memory MB] "
               "[--jobs J] [--work DIR]\n";
  std::exit(2);
}

std::vector<char> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) usage(path + ": cannot read");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// One to three mutations of `bytes`, drawn from `rng`.
std::vector<char> mutate(std::vector<char> bytes, std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) {
    return n == 0 ? std::size_t{0} : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
  };
  const int count = 1 + static_cast<int>(pick(3));
  for (int m = 0; m < count && !bytes.empty(); ++m) {
    switch (pick(6)) {
      case 0:  // a few bytes set to random values
        for (std::size_t k = 1 + pick(8); k > 0; --k) bytes[pick(bytes.size())] = static_cast<char>(rng());
        break;
      case 1:  // one bit
        bytes[pick(bytes.size())] ^= static_cast<char>(1u << pick(8));
        break;
      case 2:  // truncated
        bytes.resize(pick(bytes.size()));
        break;
      case 3: {  // a 1, 2, 4 or 8-byte field overwritten with a boundary value
        static const std::uint64_t values[] = {0,
                                               1,
                                               0x7f,
                                               0xff,
                                               0x7fff,
                                               0xffff,
                                               0x7fffffff,
                                               0xffffffff,
                                               0x7fffffffffffffff,
                                               0xffffffffffffffff,
                                               0x8000000000000000};
        const std::size_t width = std::size_t{1} << pick(4);
        if (bytes.size() < width) break;
        const std::size_t at = pick(bytes.size() - width + 1);
        const std::uint64_t v = values[pick(std::size(values))];
        std::memcpy(bytes.data() + at, &v, width);
        break;
      }
      case 4: {  // a block zeroed
        const std::size_t at = pick(bytes.size()), n = std::min(bytes.size() - at, 1 + pick(64));
        std::memset(bytes.data() + at, 0, n);
        break;
      }
      default: {  // a block copied elsewhere
        const std::size_t n = 1 + pick(std::min<std::size_t>(bytes.size(), 64));
        const std::size_t from = pick(bytes.size() - n + 1), to = pick(bytes.size() - n + 1);
        std::memmove(bytes.data() + to, bytes.data() + from, n);
        break;
      }
    }
  }
  return bytes;
}

void write_bytes(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error(path + ": cannot write");
}

enum class Outcome { ok, signal, hang, bad_exit };
struct Result {
  Outcome outcome;
  int code;  // exit code or signal
};

std::string absolute_program(const std::string& name) {
  if (name.find('/') != std::string::npos) return name;
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':'))
    if (access((dir + "/" + name).c_str(), X_OK) == 0) return dir + "/" + name;
  return name;
}

// Runs argv in `dir` with the limits; kills the whole process group after `timeout` seconds.
Result run(const std::vector<std::string>& argv, const std::string& dir, const std::string& stdin_path, double timeout,
           long memory_mb) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    setpgid(0, 0);
    if (chdir(dir.c_str()) != 0) _exit(125);
    const int in = open(stdin_path.empty() ? "/dev/null" : stdin_path.c_str(), O_RDONLY);
    const int out = open("/dev/null", O_WRONLY);
    if (in < 0 || out < 0) _exit(125);
    dup2(in, 0);
    dup2(out, 1);
    dup2(out, 2);
    if (memory_mb > 0) {
      const rlimit limit{static_cast<rlim_t>(memory_mb) << 20, static_cast<rlim_t>(memory_mb) << 20};
      setrlimit(RLIMIT_AS, &limit);
    }
    execv(args[0], args.data());
    _exit(127);
  }
  const int pidfd = static_cast<int>(syscall(SYS_pidfd_open, pid, 0));
  bool hung = false;
  if (pidfd >= 0) {
    pollfd p{pidfd, POLLIN, 0};
    int ready;
    do ready = poll(&p, 1, static_cast<int>(timeout * 1000));
    while (ready < 0 && errno == EINTR);
    hung = ready == 0;
    close(pidfd);
  } else {  // no pidfd: poll waitpid
    for (double waited = 0; waited < timeout; waited += 0.005) {
      if (waitpid(pid, nullptr, WNOHANG | WNOWAIT) != 0) break;
      usleep(5000);
    }
    hung = waitpid(pid, nullptr, WNOHANG | WNOWAIT) == 0;
  }
  if (hung) kill(-pid, SIGKILL);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (hung) return {Outcome::hang, 0};
  if (WIFSIGNALED(status)) return {Outcome::signal, WTERMSIG(status)};
  const int code = WEXITSTATUS(status);
  if (code == 0 || code == 1 || code == 2) return {Outcome::ok, code};
  return {Outcome::bad_exit, code};
}

Options parse(int argc, char** argv) {
  Options o;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    auto value = [&]() -> std::string {
      if (k + 1 >= argc) usage(a + ": missing value");
      return argv[++k];
    };
    try {
      if (a == "--spec")
        o.spec = value();
      else if (a == "--mutants")
        o.mutants = std::stol(value());
      else if (a == "--seed")
        o.seed = std::stoull(value());
      else if (a == "--timeout")
        o.timeout = std::stod(value());
      else if (a == "--memory")
        o.memory_mb = std::stol(value());
      else if (a == "--jobs")
        o.jobs = std::stoi(value());
      else if (a == "--work")
        o.work = value();
      else
        usage("unknown option " + a);
    } catch (const std::logic_error&) {
      usage(a + ": not a number");
    }
  }
  if (o.spec.empty()) usage("--spec is required");
  if (o.mutants < 0 || o.timeout <= 0 || o.memory_mb < 0 || o.jobs < 1) usage("negative or zero count");
  return o;
}

std::vector<Command> read_spec(const std::string& path) {
  std::ifstream in(path);
  if (!in) usage(path + ": cannot read");
  std::vector<Command> commands;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    Command c;
    std::string w;
    if (!(words >> c.file) || c.file[0] == '#') continue;
    while (words >> w) {
      if (w == "<{}")
        c.stdin_mutant = true;
      else
        c.argv.push_back(w);
    }
    if (c.argv.empty()) usage(path + ": no command for " + c.file);
    c.argv[0] = absolute_program(c.argv[0]);
    commands.push_back(std::move(c));
  }
  if (commands.empty()) usage(path + ": no commands");
  return commands;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const std::vector<Command> commands = read_spec(o.spec);
  std::map<std::string, std::vector<char>> originals;
  for (const auto& c : commands)
    if (!originals.count(c.file)) originals[c.file] = read_bytes(c.file);
  std::filesystem::create_directories(o.work + "/failures");

  // The work: (file, mutant number) pairs, taken in order by the job threads.
  std::vector<std::pair<std::string, long>> work;
  for (const auto& [file, bytes] : originals)
    for (long k = 0; k < o.mutants; ++k) work.emplace_back(file, k);
  std::atomic<std::size_t> next{0};
  std::mutex report_mutex;
  struct Tally {
    long runs = 0, exit0 = 0, exit1 = 0, exit2 = 0, signals = 0, hangs = 0, bad_exits = 0;
  };
  std::map<std::string, Tally> tally;
  std::vector<std::string> failures;

  auto worker = [&](int job) {
    const std::string dir = std::filesystem::absolute(o.work + "/job" + std::to_string(job)).string();
    for (std::size_t i; (i = next++) < work.size();) {
      const auto& [file, k] = work[i];
      std::mt19937_64 rng(o.seed * 0x9E3779B97F4A7C15ull +
                          std::hash<std::string>{}(std::filesystem::path(file).filename().string()) +
                          static_cast<std::uint64_t>(k));
      const std::vector<char> bytes = mutate(originals.at(file), rng);
      std::filesystem::remove_all(dir);
      std::filesystem::create_directories(dir);
      const std::string mutant = dir + "/mutant" + std::filesystem::path(file).extension().string();
      write_bytes(mutant, bytes);
      for (const auto& c : commands) {
        if (c.file != file) continue;
        std::vector<std::string> args;
        for (const auto& a : c.argv) {
          std::string s = a;
          for (std::size_t at; (at = s.find("{}")) != std::string::npos;) s.replace(at, 2, mutant);
          args.push_back(s);
        }
        const Result r = run(args, dir, c.stdin_mutant ? mutant : "", o.timeout, o.memory_mb);
        std::lock_guard lock(report_mutex);
        Tally& t = tally[c.name()];
        ++t.runs;
        if (r.outcome == Outcome::ok) {
          (r.code == 0 ? t.exit0 : r.code == 1 ? t.exit1 : t.exit2)++;
          continue;
        }
        std::string what;
        if (r.outcome == Outcome::signal) ++t.signals, what = std::string("signal ") + strsignal(r.code);
        if (r.outcome == Outcome::hang) ++t.hangs, what = "no exit after " + std::to_string(o.timeout) + " s";
        if (r.outcome == Outcome::bad_exit) ++t.bad_exits, what = "exit " + std::to_string(r.code);
        const std::string keep = o.work + "/failures/" + std::filesystem::path(file).stem().string() + "-" +
                                 std::to_string(k) + std::filesystem::path(file).extension().string();
        write_bytes(keep, bytes);
        std::string cmd;
        for (const auto& a : c.argv) cmd += (cmd.empty() ? "" : " ") + a;
        if (c.stdin_mutant) cmd += " < {}";
        std::ofstream(keep + ".txt") << what << "\n" << cmd << "\n";
        failures.push_back(keep + ": " + what + ": " + cmd);
      }
    }
    std::filesystem::remove_all(dir);
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < o.jobs; ++j) threads.emplace_back(worker, j);
  for (auto& t : threads) t.join();

  std::printf("%-22s %7s %7s %7s %7s %7s %7s %9s\n", "command", "runs", "exit0", "exit1", "exit2", "signals", "hangs",
              "bad-exit");
  Tally total;
  for (const auto& [name, t] : tally) {
    std::printf("%-22s %7ld %7ld %7ld %7ld %7ld %7ld %9ld\n", name.c_str(), t.runs, t.exit0, t.exit1, t.exit2,
                t.signals, t.hangs, t.bad_exits);
    total.runs += t.runs, total.exit0 += t.exit0, total.exit1 += t.exit1, total.exit2 += t.exit2;
    total.signals += t.signals, total.hangs += t.hangs, total.bad_exits += t.bad_exits;
  }
  std::printf("%-22s %7ld %7ld %7ld %7ld %7ld %7ld %9ld\n", "total", total.runs, total.exit0, total.exit1, total.exit2,
              total.signals, total.hangs, total.bad_exits);
  std::printf("mutants: %ld of each of %zu files (%zu in all), seed %llu\n", o.mutants, originals.size(), work.size(),
              static_cast<unsigned long long>(o.seed));
  for (const auto& f : failures) std::printf("FAIL %s\n", f.c_str());
  return failures.empty() ? 0 : 1;
}
