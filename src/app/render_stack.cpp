#include "app/render_stack.h"

#include <pthread.h>
#include <tbb/global_control.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace prism {
namespace {

struct Job {
    const std::function<int()> *main;
    int result;
};

void *RunJob(void *arg) {
    Job *job = static_cast<Job *>(arg);
    job->result = (*job->main)();
    return nullptr;
}

}  // namespace

int RunOnRenderStack(const std::function<int()> &main) {
    // TBB creates its workers when it is first used (Embree's BVH builds, the tile loop);
    // the setting applies to every worker created while it is held.
    tbb::global_control workers(tbb::global_control::thread_stack_size, RenderStackBytes);
    pthread_attr_t attr;
    pthread_t thread;
    Job job{&main, 0};
    int err = pthread_attr_init(&attr);
    if (err == 0) err = pthread_attr_setstacksize(&attr, RenderStackBytes);
    if (err == 0) err = pthread_create(&thread, &attr, RunJob, &job);
    pthread_attr_destroy(&attr);
    if (err != 0) {
        // No thread of that size (address space limited by ulimit -v, say): render here, on
        // this thread's stack, rather than not at all.
        std::fprintf(stderr,
                     "warning: no %zu MB render thread (%s); rendering on the main "
                     "thread, whose stack may not hold the deepest maxdepth\n",
                     RenderStackBytes >> 20, std::strerror(err));
        return main();
    }
    pthread_join(thread, nullptr);
    return job.result;
}

}  // namespace prism
