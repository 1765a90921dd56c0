#pragma once
// One writer per run directory: two runs writing the same log and trajectory would leave
// neither. The lock is an flock on DIR/pedesis.lock, which holds the holder's process id
// and host for the message a second run gets. The kernel lets go of an flock when its
// process dies, however it dies, so a lock left by a killed run never blocks a resume.
#include <filesystem>
#include <string>

namespace pedesis {

inline constexpr const char* run_directory_lock_file = "pedesis.lock";

class RunDirectoryLock {
  public:
    // Creates `dir` if needed and takes its lock at once; InputError naming the process
    // that holds it (its id and host) if another does.
    explicit RunDirectoryLock(const std::filesystem::path& dir);
    // Removes the lock file, then lets go; and removes the directory if it made it and
    // nothing was written there (a config refused in set-up leaves no run directory).
    ~RunDirectoryLock();
    RunDirectoryLock(const RunDirectoryLock&) = delete;
    RunDirectoryLock& operator=(const RunDirectoryLock&) = delete;

  private:
    std::filesystem::path dir_, file_;
    bool made_dir_ = false;
    int fd_ = -1;
};

} // namespace pedesis
