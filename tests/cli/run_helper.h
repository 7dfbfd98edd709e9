#pragma once
// Helpers for the end-to-end tests of the ranryu binary: a fresh temporary folder per test, and a
// runner that executes a command (no shell: argv as given) in that folder and captures its exit code,
// stdout and stderr separately.
//
// run() forks; the child moves to the folder, reads /dev/null, writes stdout and stderr to two
// temporary files (created with mkstemp and unlinked at once, so nothing is left behind even if the
// test crashes), and execs. The child leads its own process group, so a command that runs past its
// time limit (xvfb-run and its Xvfb included) is killed as a whole. start() and wait() are run() in
// two halves, for a test that acts on the command while it runs (a signal); run_in_terminal() runs
// it on a pseudo-terminal instead, its stdout and stderr both the terminal.
//
// Set RANRYU_KEEP_TEST_TMP=1 to keep the temporary folders for a look after the run.
#include <fcntl.h>
#include <poll.h>
#include <pty.h>
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

// The binary under test: the build's own, or RANRYU_TEST_BIN (scripts/sanitize.sh runs the fuzz
// corpus against the sanitizer build's binary this way).
inline const std::string kBin = [] {
    const char* bin = std::getenv("RANRYU_TEST_BIN");
    return std::string(bin && *bin ? bin : RANRYU_BIN);
}();
inline const fs::path kData = RANRYU_TEST_DATA;
// The repository (tests/data/../..) and its glsl/ tree.
inline fs::path source_dir() { return (kData / ".." / "..").lexically_normal(); }
inline fs::path glsl_dir() { return source_dir() / "glsl"; }
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
    std::vector<std::pair<std::string, std::string>> set_env;   // and set in it
};

namespace detail {

inline int temp_fd() {
    char name[] = "/tmp/ranryu-cli-capture-XXXXXX";
    const int fd = mkostemp(name, O_CLOEXEC);   // the child gets it only as its dup2()ed 1 or 2
    if (fd < 0) throw std::runtime_error("mkostemp: " + std::string(std::strerror(errno)));
    unlink(name);   // the open descriptor keeps the data; nothing stays on disk
    return fd;
}

// Everything written to `fd` so far (pread: the child may still be writing at its own offset).
inline std::string read_all(int fd) {
    std::string text;
    char buf[65536];
    for (off_t at = 0;;) {
        const ssize_t n = pread(fd, buf, sizeof buf, at);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        text.append(buf, std::size_t(n));
        at += n;
    }
    return text;
}

// In the child, after fork: the folder and environment of `opt`, then exec. Only async-signal-safe
// calls (plus setenv/unsetenv, fine in a single-threaded parent); never returns.
[[noreturn]] inline void exec_child(const std::vector<std::string>& argv, const RunOptions& opt) {
    if (!opt.cwd.empty() && chdir(opt.cwd.c_str()) != 0) {
        const char msg[] = "run_helper: cannot chdir to the test folder\n";
        (void)!write(2, msg, sizeof msg - 1);
        _exit(126);
    }
    for (const std::string& v : opt.unset_env) unsetenv(v.c_str());
    for (const auto& [name, value] : opt.set_env) setenv(name.c_str(), value.c_str(), 1);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execvp(args[0], args.data());
    const char msg[] = "run_helper: exec failed\n";
    (void)!write(2, msg, sizeof msg - 1);
    _exit(127);
}

// Waits for `pid` until `deadline`, then kills its process group. Fills exit_code and timed_out.
inline void reap(pid_t pid, std::chrono::steady_clock::time_point deadline, Result& r) {
    int status = 0;
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
}

inline std::string quoted(const std::vector<std::string>& argv) {
    std::string s;
    for (const std::string& a : argv) s += (s.empty() ? "" : " ") + ("'" + a + "'");
    return s;
}

}  // namespace detail

// A command started by start(): wait() for its Result, or look at its output meanwhile.
struct Child {
    pid_t pid = -1;
    int out_fd = -1, err_fd = -1;
    std::vector<std::string> argv;
    std::chrono::steady_clock::time_point deadline;
    std::chrono::seconds timeout{};

    std::string err_so_far() const { return detail::read_all(err_fd); }
};

// Starts argv[0] (looked up on PATH if it has no '/') with argv, and returns at once.
inline Child start(const std::vector<std::string>& argv, const RunOptions& opt = {}) {
    if (argv.empty()) throw std::invalid_argument("run: empty argv");
    Child c;
    c.argv = argv;
    c.timeout = opt.timeout;
    c.out_fd = detail::temp_fd();
    c.err_fd = detail::temp_fd();
    std::fflush(stdout);
    std::fflush(stderr);
    c.pid = fork();
    if (c.pid < 0) throw std::runtime_error("fork: " + std::string(std::strerror(errno)));
    if (c.pid == 0) {
        setpgid(0, 0);
        const int in_fd = open("/dev/null", O_RDONLY);
        if (in_fd < 0 || dup2(in_fd, 0) < 0 || dup2(c.out_fd, 1) < 0 || dup2(c.err_fd, 2) < 0) _exit(126);
        detail::exec_child(argv, opt);
    }
    setpgid(c.pid, c.pid);   // also here: no race with the child's own call
    c.deadline = std::chrono::steady_clock::now() + opt.timeout;
    return c;
}

// Waits for a started command (killing it past its time limit) and collects its output.
inline Result wait(Child& c) {
    Result r;
    detail::reap(c.pid, c.deadline, r);
    r.out = detail::read_all(c.out_fd);
    r.err = detail::read_all(c.err_fd);
    close(c.out_fd);
    close(c.err_fd);
    if (r.timed_out) r.err += "\nrun_helper: killed after " + std::to_string(c.timeout.count()) + " s: " + detail::quoted(c.argv) + "\n";
    return r;
}

// Runs argv[0] with argv, and waits for it.
inline Result run(const std::vector<std::string>& argv, const RunOptions& opt = {}) {
    Child c = start(argv, opt);
    return wait(c);
}

// Runs argv on a new pseudo-terminal `columns` wide (stdin, stdout and stderr all the terminal) and
// waits for it. Result::out is everything the terminal received, as it came ('\n' arrives as "\r\n");
// Result::err is empty.
inline Result run_in_terminal(const std::vector<std::string>& argv, const RunOptions& opt = {}, int columns = 200) {
    if (argv.empty()) throw std::invalid_argument("run_in_terminal: empty argv");
    std::fflush(stdout);
    std::fflush(stderr);
    winsize ws{};
    ws.ws_row = 40;
    ws.ws_col = static_cast<unsigned short>(columns);
    int master = -1;
    const pid_t pid = forkpty(&master, nullptr, nullptr, &ws);   // the child leads a new session
    if (pid < 0) throw std::runtime_error("forkpty: " + std::string(std::strerror(errno)));
    if (pid == 0) detail::exec_child(argv, opt);

    // Read as it comes, or the child blocks on a full terminal; the end is EIO once it has exited.
    Result r;
    const auto deadline = std::chrono::steady_clock::now() + opt.timeout;
    char buf[4096];
    for (;;) {
        pollfd p{master, POLLIN, 0};
        const int ready = poll(&p, 1, 50);
        if (ready > 0) {
            const ssize_t n = read(master, buf, sizeof buf);
            if (n > 0) {
                r.out.append(buf, std::size_t(n));
                continue;
            }
            if (n < 0 && errno == EINTR) continue;
            break;   // EIO or end: every copy of the terminal's other side is closed
        }
        if (ready < 0 && errno != EINTR) break;
        if (std::chrono::steady_clock::now() > deadline) break;
    }
    detail::reap(pid, deadline, r);
    close(master);
    if (r.timed_out) r.out += "\nrun_helper: killed after " + std::to_string(opt.timeout.count()) + " s: " + detail::quoted(argv) + "\n";
    return r;
}

// `ranryu ARGS...` in folder `cwd`.
inline Result run_ranryu(const fs::path& cwd, std::vector<std::string> args, RunOptions opt = {}) {
    args.insert(args.begin(), kBin);
    opt.cwd = cwd;
    return run(args, opt);
}
inline Child start_ranryu(const fs::path& cwd, std::vector<std::string> args, RunOptions opt = {}) {
    args.insert(args.begin(), kBin);
    opt.cwd = cwd;
    return start(args, opt);
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
