// The little prism-mpi needs of MPI: messages of bytes, waits that sleep instead of spinning,
// and the agreement after every rank's setup. Only the main thread of each rank calls MPI.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace prism::mpi {

// Message tags of the two protocols (mpi_render.cpp, mpi_batch.cpp).
enum Tag : int {
    TagTiles = 1,    // worker → 0: finished tiles (none in the first message: a request)
    TagAssign = 2,   // 0 → worker: the next work, or none: stop
    TagStats = 3,    // worker → 0: its totals, after the stop
    TagError = 4,    // worker → 0: an error that ends the job
    TagRequest = 5,  // worker → 0: a free slot (batch)
    TagResult = 6,   // worker → 0: one scene's record (batch)
    TagDone = 7,     // worker → 0: no more work will be asked for (batch)
};

int Rank();
int Size();

// Set by SIGINT or SIGTERM (mpirun sends SIGTERM to every rank when one dies or the job is
// cancelled) once InstallStopHandler ran.
extern volatile int g_stop;
void InstallStopHandler();

// A received message.
struct Message {
    int source = -1, tag = -1;
    std::vector<uint8_t> bytes;
};
// Waits for the next message (from `source`, MPI_ANY_SOURCE for any) sleeping between polls,
// so a waiting rank leaves its core to the renderers (Open MPI's blocking receive spins).
// Returns false when g_stop was raised first.
bool Receive(Message *m, int source = MPI_ANY_SOURCE, int tag = MPI_ANY_TAG);
void Send(int dest, int tag, const std::vector<uint8_t> &bytes);
// Completes `req` sleeping between tests.
void Wait(MPI_Request *req);

// Every rank reports how its setup went (exit status, message); if any failed, rank 0 prints
// one error (its own, else the first failing rank's, named) and every rank gets that status.
// Returns 0 when all succeeded.
int AgreeOnSetup(int status, const std::string &message);

// Appending and reading plain values (the ranks run the same binary on the same kind of
// machine, so values go as bytes).
class Writer {
  public:
    template <typename T>
    void Put(const T &v) {
        size_t n = buf_.size();
        buf_.resize(n + sizeof(T));
        std::memcpy(buf_.data() + n, &v, sizeof(T));
    }
    void PutBytes(const void *p, size_t n) {
        size_t o = buf_.size();
        buf_.resize(o + n);
        if (n) std::memcpy(buf_.data() + o, p, n);
    }
    void PutString(const std::string &s) {
        Put(uint64_t(s.size()));
        PutBytes(s.data(), s.size());
    }
    std::vector<uint8_t> &Bytes() { return buf_; }

  private:
    std::vector<uint8_t> buf_;
};

class Reader {
  public:
    explicit Reader(const std::vector<uint8_t> &b) : b_(b) {}
    template <typename T>
    T Get() {
        T v;
        GetBytes(&v, sizeof(T));
        return v;
    }
    void GetBytes(void *p, size_t n);  // throws std::runtime_error past the end
    std::string GetString();
    bool AtEnd() const { return pos_ == b_.size(); }
    size_t Remaining() const { return b_.size() - pos_; }

  private:
    const std::vector<uint8_t> &b_;
    size_t pos_ = 0;
};

}  // namespace prism::mpi
