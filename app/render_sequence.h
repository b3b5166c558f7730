// bounce render --path: a camera path rendered frame by frame (issue 58, "Sequences"), one frame per step
// with no still frames, its frames as EXR (every K-th and the last) and a record of every frame's GPU time.
#pragma once

#include "app/options.h"

namespace bounce::app {

// The --help lines of --path, --every and --indirect-scale.
extern const char* const kSequenceOptionsHelp;

// Runs `bounce render` with --path given: the options are render's. Returns the exit status; bad input
// (the path file, a refused option, an --out that is not a folder) throws UsageError before anything is
// written.
int renderSequence(const Options& o);

} // namespace bounce::app
