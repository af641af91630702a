// Removal of brdfcl's output temporaries when the process is interrupted: SIGINT, SIGTERM and
// SIGHUP unlink every temporary the process has open, then exit with 128 + the signal number.
#pragma once

namespace brdfcl {

// Installs the handlers for SIGINT, SIGTERM and SIGHUP (a signal that is ignored when this is
// called, e.g. SIGHUP under nohup, stays ignored). Call it first in main, before any thread
// starts; the handler is async-signal-safe and may run on any thread (PoCL's workers included).
// Stale temporaries of processes that no longer exist are removed independently of this, by
// the next write to their directory.
void installSignalCleanup();

}  // namespace brdfcl
