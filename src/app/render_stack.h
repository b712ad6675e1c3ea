// The stack every rendering thread of prism and prism-mpi runs on.
#pragma once

#include <cstddef>
#include <functional>

namespace prism {

// The Whitted/distribution kernel recurses once per specular bounce (Li, Shade, AddSpecular:
// about 4 KB a level in a Release build, two to three times that under ASan), and maxdepth
// goes to 1000 (MaxTraceDepth), past the 4 MB TBB gives its workers and the 8 MB a main
// thread usually has. Address space only: a thread touches the pages it uses.
inline constexpr size_t RenderStackBytes = size_t(64) << 20;

// Runs main on a new thread whose stack is RenderStackBytes, with TBB's workers given the
// same (a process-wide setting held until main returns; call this before anything starts
// TBB), and returns what main returns. The calling thread only waits.
int RunOnRenderStack(const std::function<int()> &main);

}  // namespace prism
