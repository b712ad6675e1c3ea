// prism-mpi's subcommands; each runs on every rank and returns the rank's exit status.
#pragma once

#include "app/batch_jobs.h"
#include "app/render_options.h"

namespace prism::mpi {

int RunMpiRender(const RenderArgs &a);
int RunMpiBatch(const BatchArgs &a);

}  // namespace prism::mpi
