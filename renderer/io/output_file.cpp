#include "io/output_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <pthread.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace softtrace {

namespace fs = std::filesystem;

namespace {

double now_seconds() {
  timespec t{};
  ::clock_gettime(CLOCK_REALTIME, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// Taken when the program is loaded: the run's start for remove_stale_temporaries.
const double g_process_start = now_seconds();

struct Pending {
  std::string tmp;
  int fd;                 // holds the flock until the file is renamed or removed
  std::thread::id owner;  // the thread writing it: only its own forget or abandon touches it
};

// The lock is held from creating a file to recording it, so whoever abandons the writes (the
// command line's SIGINT/SIGTERM handler, cli/signals.h) sees every file that exists. The list is
// process-wide for that handler; each thread's writes are its own, so that threads writing at
// once (Python renders) never remove or forget each other's files.
std::mutex g_pending_mutex;
std::vector<Pending> g_pending;

// The pending files' lock, taken with SIGINT and SIGTERM blocked in this thread until it is
// released: a handler that interrupted its holder would wait for it forever. A handler on another
// thread waits the moment it is held.
class PendingLock {
 public:
  PendingLock() {
    sigemptyset(&interrupts_);
    sigaddset(&interrupts_, SIGINT);
    sigaddset(&interrupts_, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &interrupts_, &before_);
    g_pending_mutex.lock();
  }
  ~PendingLock() {
    g_pending_mutex.unlock();
    pthread_sigmask(SIG_SETMASK, &before_, nullptr);
  }
  PendingLock(const PendingLock&) = delete;
  PendingLock& operator=(const PendingLock&) = delete;

 private:
  sigset_t interrupts_, before_;
};

// What a non-regular file is, for the refusal: only regular files are replaced, since renaming
// over a FIFO or a device node (through a link, /dev/null) would put a regular file in its place.
const char* kind_of(const struct stat& st) {
  if (S_ISFIFO(st.st_mode)) return "a FIFO";
  if (S_ISCHR(st.st_mode)) return "a character device";
  if (S_ISBLK(st.st_mode)) return "a block device";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  if (S_ISDIR(st.st_mode)) return "a folder";
  return "not a regular file";
}

// Throws `E` when `target` exists and is not a regular file.
template <class E>
void require_regular_or_absent(const std::string& target, const std::string& display) {
  struct stat st {};
  if (::lstat(target.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    throw E(display + ": is " + std::string(kind_of(st)) +
            "; outputs must be regular files or links to them");
}

bool is_temp_suffix(const char* s) {
  if (std::strlen(s) != 6) return false;
  return std::all_of(s, s + 6, [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
  });
}

}  // namespace

double process_start_time() {
  return g_process_start;
}

std::string output_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string resolve_output_target(const std::string& path) {
  fs::path p(path);
  std::error_code ec;
  for (int hops = 0; fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
    if (hops == 40) throw std::invalid_argument(path + ": too many levels of symbolic links");
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) throw std::invalid_argument(path + ": cannot read the link: " + ec.message());
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  return p.string();
}

void check_output_path(const std::string& path, const char* const* extensions) {
  const std::string ext = output_extension(path);
  std::string expected;
  bool known = false;
  for (auto e = extensions; *e; ++e) {
    known |= ext == *e;
    expected += std::string(expected.empty() ? "" : " or ") + *e;
  }
  if (!known)
    throw std::invalid_argument(path + ": unsupported output format '" + ext + "' (expected " +
                                expected + ")");
  const fs::path target(resolve_output_target(path));
  fs::path dir = target.parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw std::invalid_argument(path + ": the folder '" + dir.string() + "' does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw std::invalid_argument(path + ": the folder '" + dir.string() + "' is not writable");
  if (fs::is_directory(target, ec)) throw std::invalid_argument(path + ": is a folder");
  require_regular_or_absent<std::invalid_argument>(target.string(), path);
}

int remove_stale_temporaries(const std::string& target, double started) {
  const fs::path t(target);
  const fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
  const std::string prefix = "." + t.filename().string() + ".";
  DIR* d = ::opendir(dir.c_str());
  if (!d) return 0;
  int removed = 0;
  while (const dirent* e = ::readdir(d)) {
    if (std::strncmp(e->d_name, prefix.c_str(), prefix.size()) != 0 ||
        !is_temp_suffix(e->d_name + prefix.size()))
      continue;
    const std::string name = (dir / e->d_name).string();
    // O_NOFOLLOW: never act on a link planted under that name.
    const int fd = ::open(name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) continue;
    struct stat st {};
    const bool candidate = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) &&
                           st.st_uid == ::geteuid() &&
                           double(st.st_mtim.tv_sec) + 1e-9 * double(st.st_mtim.tv_nsec) < started;
    // A live writer holds the lock until it renames or removes the file.
    if (candidate && ::flock(fd, LOCK_EX | LOCK_NB) == 0) {
      struct stat now {};
      // Still the same file under that name: remove it while we hold its lock.
      if (::lstat(name.c_str(), &now) == 0 && now.st_ino == st.st_ino && now.st_dev == st.st_dev &&
          ::unlink(name.c_str()) == 0)
        ++removed;
    }
    ::close(fd);
  }
  ::closedir(d);
  return removed;
}

std::string create_pending_temp(const std::string& target, const std::string& display) {
  const fs::path t(target);
  const fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
  std::string tmp = (dir / ("." + t.filename().string() + ".XXXXXX")).string();
  const PendingLock lock;
  const int fd = ::mkostemp(tmp.data(), O_CLOEXEC);
  if (fd < 0)
    throw std::runtime_error(display + ": cannot create a file in '" + dir.string() +
                             "': " + std::strerror(errno));
  ::flock(fd, LOCK_EX);  // new and private: cannot block
  g_pending.push_back({tmp, fd, std::this_thread::get_id()});
  return tmp;
}

namespace {

// The descriptor that holds `tmp`'s lock, open since create_pending_temp made the file; -1 when
// the calling thread has no such pending file.
int pending_descriptor(const std::string& tmp) {
  const PendingLock lock;
  const std::thread::id self = std::this_thread::get_id();
  for (const auto& p : g_pending)
    if (p.owner == self && p.tmp == tmp) return p.fd;
  return -1;
}

}  // namespace

void commit_temp(const std::string& tmp, const std::string& target, const std::string& display) {
  // The file's lock holds it open already: synced through that descriptor (fsync syncs the file,
  // whichever descriptor wrote), it takes no open and close of its own. Another thread's file is
  // not this one's to sync, rename or remove.
  const int fd = pending_descriptor(tmp);
  if (fd < 0) throw std::runtime_error(display + ": not a file this thread is writing");
  try {
    // The target may have become a FIFO or a device since check_output_path.
    require_regular_or_absent<std::runtime_error>(target, display);
    // The writers checked every write and close; the data must also be on the disk before the
    // rename makes it the output (a delayed write error shows in fsync).
    if (::fsync(fd) != 0)
      throw std::runtime_error(display + ": cannot write the file: " + std::strerror(errno));
  } catch (const std::exception&) {
    ::unlink(tmp.c_str());
    throw;
  }
  // mkstemp makes the file private; give it the usual permissions of a new file.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  std::error_code ec;
  fs::permissions(tmp, static_cast<fs::perms>(0666 & ~mask), ec);
  if (!ec) fs::rename(tmp, target, ec);
  if (ec) {
    ::unlink(tmp.c_str());
    throw std::runtime_error(display + ": cannot replace the file: " + ec.message());
  }
}

namespace {

// Closes (and with `remove`, first removes) the calling thread's pending files and forgets them.
void release_own_pending(bool remove) {
  const PendingLock lock;
  const std::thread::id self = std::this_thread::get_id();
  const auto own = std::stable_partition(g_pending.begin(), g_pending.end(),
                                         [&](const Pending& p) { return p.owner != self; });
  for (auto p = own; p != g_pending.end(); ++p) {
    if (remove) ::unlink(p->tmp.c_str());  // renamed ones are gone: ENOENT
    ::close(p->fd);
  }
  g_pending.erase(own, g_pending.end());
}

}  // namespace

void forget_pending_writes() {
  release_own_pending(false);
}

void abandon_pending_writes() {
  release_own_pending(true);
}

void abandon_pending_writes_and_exit(int status) {
  g_pending_mutex.lock();  // held to the end: no temporary file can be created after these
  for (const auto& p : g_pending) ::unlink(p.tmp.c_str());
  _exit(status);
}

}  // namespace softtrace
