// Removal of brdfcl's output temporaries when the process is interrupted: SIGINT, SIGTERM, SIGHUP
// and SIGPIPE unlink every temporary the process has open, then exit with 128 + the signal number.
#pragma once

namespace brdfcl {

// Installs the handlers for SIGINT, SIGTERM, SIGHUP and SIGPIPE (a signal that is ignored when
// this is called, e.g. SIGHUP under nohup, stays ignored; an ignored SIGPIPE makes a closed pipe
// the write error EPIPE). Call it first in main, before any thread
// starts; the handler is async-signal-safe and may run on any thread (PoCL's workers included).
// Temporaries of processes of this host that no longer exist, older than an hour, are removed
// independently of this, by the next write to their directory.
void installSignalCleanup();

}  // namespace brdfcl
