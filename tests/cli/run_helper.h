#pragma once
// Helpers for the end-to-end tests of the ranryu binary: a fresh temporary folder per test, and a
// runner that executes a command (no shell: argv as given) in that folder and captures its exit code,
// stdout and stderr separately.
//
// run() forks; the child moves to the folder, reads /dev/null, writes stdout and stderr to two
// temporary files (created with mkstemp and unlinked at once, so nothing is left behind even if the
// test crashes), and execs. The child leads its own process group, so a command that runs past its
// time limit (xvfb-run and its Xvfb included) is killed as a whole.
//
// Set RANRYU_KEEP_TEST_TMP=1 to keep the temporary folders for a look after the run.
#include <fcntl.h>
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace ranryu::test {

namespace fs = std::filesystem;

inline const std::string kBin = RANRYU_BIN;
inline const fs::path kData = RANRYU_TEST_DATA;
// The repository's glsl/ tree (tests/data/../../glsl).
inline fs::path glsl_dir() { return (kData / ".." / ".." / "glsl").lexically_normal(); }
inline fs::path scene_file(const std::string& name) { return kData / "scenes" / name; }

// A folder made with mkdtemp under /tmp, removed (with everything in it) when the object dies.
class TempDir {
public:
    TempDir() {
        std::string tmpl = "/tmp/ranryu-cli-XXXXXX";
        if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp: " + std::string(std::strerror(errno)));
        path_ = tmpl;
    }
    ~TempDir() {
        const char* keep = std::getenv("RANRYU_KEEP_TEST_TMP");
        if (keep && std::string(keep) == "1") return;
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const fs::path& path() const { return path_; }
    fs::path operator/(const std::string& rel) const { return path_ / rel; }
    std::string str(const std::string& rel) const { return (path_ / rel).string(); }

private:
    fs::path path_;
};

struct Result {
    int exit_code = -1;      // the process's exit status; 128 + N if killed by signal N
    bool timed_out = false;  // killed for running past the limit
    std::string out, err;    // stdout, stderr

    std::vector<std::string> err_lines() const { return split_lines(err); }
    std::vector<std::string> out_lines() const { return split_lines(out); }

    static std::vector<std::string> split_lines(const std::string& text) {
        std::vector<std::string> lines;
        std::istringstream in(text);
        for (std::string line; std::getline(in, line);) lines.push_back(line);
        return lines;
    }
    // For INFO(): everything a failure report needs.
    std::string describe() const {
        return "exit code " + std::to_string(exit_code) + (timed_out ? " (timed out)" : "") + "\n--- stdout ---\n" + out +
               "--- stderr ---\n" + err + "--------------";
    }
};

struct RunOptions {
    fs::path cwd;                         // empty: the test process's folder
    std::chrono::seconds timeout{60};     // generous: llvmpipe on 2 cores under a loaded CI machine
    std::vector<std::string> unset_env;   // variables removed from the child's environment
};

namespace detail {

inline int temp_fd() {
    char name[] = "/tmp/ranryu-cli-capture-XXXXXX";
    const int fd = mkostemp(name, O_CLOEXEC);   // the child gets it only as its dup2()ed 1 or 2
    if (fd < 0) throw std::runtime_error("mkostemp: " + std::string(std::strerror(errno)));
    unlink(name);   // the open descriptor keeps the data; nothing stays on disk
    return fd;
}

inline std::string read_all(int fd) {
    std::string text;
    if (lseek(fd, 0, SEEK_SET) < 0) return text;
    char buf[65536];
    for (;;) {
        const ssize_t n = read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        text.append(buf, std::size_t(n));
    }
    return text;
}

inline std::string quoted(const std::vector<std::string>& argv) {
    std::string s;
    for (const std::string& a : argv) s += (s.empty() ? "" : " ") + ("'" + a + "'");
    return s;
}

}  // namespace detail

// Runs argv[0] (looked up on PATH if it has no '/') with argv, and waits for it.
inline Result run(const std::vector<std::string>& argv, const RunOptions& opt = {}) {
    if (argv.empty()) throw std::invalid_argument("run: empty argv");
    const int out_fd = detail::temp_fd();
    const int err_fd = detail::temp_fd();
    std::fflush(stdout);
    std::fflush(stderr);
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork: " + std::string(std::strerror(errno)));
    if (pid == 0) {
        // Child: only async-signal-safe calls until exec (plus unsetenv, fine in a single-threaded parent).
        setpgid(0, 0);
        const int in_fd = open("/dev/null", O_RDONLY);
        if (in_fd < 0 || dup2(in_fd, 0) < 0 || dup2(out_fd, 1) < 0 || dup2(err_fd, 2) < 0) _exit(126);
        if (!opt.cwd.empty() && chdir(opt.cwd.c_str()) != 0) {
            const char msg[] = "run_helper: cannot chdir to the test folder\n";
            (void)!write(2, msg, sizeof msg - 1);
            _exit(126);
        }
        for (const std::string& v : opt.unset_env) unsetenv(v.c_str());
        std::vector<char*> args;
        for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        execvp(args[0], args.data());
        const char msg[] = "run_helper: exec failed\n";
        (void)!write(2, msg, sizeof msg - 1);
        _exit(127);
    }
    setpgid(pid, pid);   // also here: no race with the child's own call

    Result r;
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + opt.timeout;
    for (;;) {
        const pid_t w = waitpid(pid, &status, WNOHANG);
        if (w == pid) break;
        if (w < 0 && errno != EINTR) break;
        if (std::chrono::steady_clock::now() > deadline) {
            r.timed_out = true;
            kill(-pid, SIGKILL);
            while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
    else if (WIFSIGNALED(status)) r.exit_code = 128 + WTERMSIG(status);
    r.out = detail::read_all(out_fd);
    r.err = detail::read_all(err_fd);
    close(out_fd);
    close(err_fd);
    if (r.timed_out) r.err += "\nrun_helper: killed after " + std::to_string(opt.timeout.count()) + " s: " + detail::quoted(argv) + "\n";
    return r;
}

// `ranryu ARGS...` in folder `cwd`.
inline Result run_ranryu(const fs::path& cwd, std::vector<std::string> args, RunOptions opt = {}) {
    args.insert(args.begin(), kBin);
    opt.cwd = cwd;
    return run(args, opt);
}

// ---- small file utilities ----

inline std::string read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + p.string());
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

inline void write_file(const fs::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary);
    out << text;
    if (!out.flush()) throw std::runtime_error("cannot write " + p.string());
}

// The names of the entries of a folder, sorted.
inline std::vector<std::string> list_dir(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

inline bool on_path(const std::string& program) {
    const char* path = std::getenv("PATH");
    if (!path) return false;
    std::istringstream dirs(path);
    for (std::string d; std::getline(dirs, d, ':');) {
        if (d.empty()) continue;
        const fs::path p = fs::path(d) / program;
        if (access(p.c_str(), X_OK) == 0 && fs::is_regular_file(p)) return true;
    }
    return false;
}

inline bool env_is(const char* name, const std::string& value) {
    const char* v = std::getenv(name);
    return v && value == v;
}

}  // namespace ranryu::test
