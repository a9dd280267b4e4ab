#pragma once
// Each verb of the `meadow` command lives in its own file and registers itself here.
// A verb is added only when it works end to end.
#include <CLI/CLI.hpp>

namespace meadow::cli {}  // namespace meadow::cli
