#pragma once
// Waiting for a child process and naming how it ended: shared by the run executor, the TetGen
// peer and the plot.
#include <sys/types.h>

#include <string>

namespace dtlab::experiments {

// waitpid() until it returns for `pid` (retried on EINTR); the wait status.
int wait_for(pid_t pid);

// "11 (SEGV)"; the number alone for a signal without an abbreviation (real-time signals).
std::string signal_name(int signal);

}  // namespace dtlab::experiments
