// What was built: the version and the commit (cmake/GitHash.cmake writes gitHash() at every
// build), named in capture manifests and bench reports.
#pragma once

namespace gb {

// The commit of the checkout at build time ("abc123def456", "...-dirty" with uncommitted changes
// to tracked files, "unknown" outside git).
const char* gitHash();

}  // namespace gb
