#include "tools/mpi/mpi_comm.h"

#include <signal.h>

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <thread>

namespace prism::mpi {

namespace {
// Between polls: short enough that a worker asking for tiles waits little (tiles take
// milliseconds), long enough that a waiting rank uses almost no CPU.
constexpr auto PollSleep = std::chrono::microseconds(100);
void OnStop(int) { g_stop = 1; }
}  // namespace

volatile int g_stop = 0;

int Rank() {
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

int Size() {
    int s = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &s);
    return s;
}

void InstallStopHandler() {
    struct sigaction sa {};
    sa.sa_handler = OnStop;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

bool Receive(Message *m, int source, int tag) {
    MPI_Status st;
    int flag = 0;
    while (true) {
        MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, &st);
        if (flag) break;
        if (g_stop) return false;
        std::this_thread::sleep_for(PollSleep);
    }
    int count = 0;
    MPI_Get_count(&st, MPI_BYTE, &count);
    m->bytes.resize(size_t(count));
    m->source = st.MPI_SOURCE;
    m->tag = st.MPI_TAG;
    MPI_Recv(m->bytes.data(), count, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    return true;
}

void Send(int dest, int tag, const std::vector<uint8_t> &bytes) {
    MPI_Request req;
    MPI_Isend(bytes.data(), int(bytes.size()), MPI_BYTE, dest, tag, MPI_COMM_WORLD, &req);
    Wait(&req);
}

void Wait(MPI_Request *req) {
    int done = 0;
    while (true) {
        MPI_Test(req, &done, MPI_STATUS_IGNORE);
        if (done) return;
        std::this_thread::sleep_for(PollSleep);
    }
}

int AgreeOnSetup(int status, const std::string &message) {
    const int rank = Rank(), size = Size();
    std::vector<int> all(size_t(size), 0);
    MPI_Request req;
    MPI_Igather(&status, 1, MPI_INT, all.data(), 1, MPI_INT, 0, MPI_COMM_WORLD, &req);
    Wait(&req);
    int agreed = 0, from = -1;
    if (rank == 0) {
        for (int r = 0; r < size && from < 0; ++r)
            if (all[size_t(r)] != 0) from = r, agreed = all[size_t(r)];
    }
    int decision[2] = {agreed, from};
    MPI_Ibcast(decision, 2, MPI_INT, 0, MPI_COMM_WORLD, &req);
    Wait(&req);
    agreed = decision[0], from = decision[1];
    // The failing rank's message goes to rank 0, which prints it once (its own as it is: a
    // scene error already names file:line:col).
    if (from > 0) {
        if (rank == from) {
            Send(0, TagError, std::vector<uint8_t>(message.begin(), message.end()));
        } else if (rank == 0) {
            Message m;
            Receive(&m, from, TagError);
            std::fprintf(stderr, "rank %d: %s\n", from,
                         std::string(m.bytes.begin(), m.bytes.end()).c_str());
        }
    } else if (from == 0 && rank == 0) {
        std::fprintf(stderr, "%s\n", message.c_str());
    }
    return agreed;
}

void Reader::GetBytes(void *p, size_t n) {
    if (n > b_.size() - pos_) throw std::runtime_error("malformed message between ranks");
    if (n) std::memcpy(p, b_.data() + pos_, n);
    pos_ += n;
}

std::string Reader::GetString() {
    uint64_t n = Get<uint64_t>();
    if (n > b_.size() - pos_) throw std::runtime_error("malformed message between ranks");
    std::string s(reinterpret_cast<const char *>(b_.data() + pos_), size_t(n));
    pos_ += size_t(n);
    return s;
}

}  // namespace prism::mpi
