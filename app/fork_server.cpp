#include "app/fork_server.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <stdexcept>

#include "app/image_files.hpp"
#include "common/end_with_parent.hpp"
#include "platform/runs/run_queue.hpp"

namespace rtsim::app {

namespace {

// A request: the log's path, then the arguments, each ended by a NUL. Replies: "P <pid>" when
// the child runs (or "E <why>" if it could not start), then "S <wait status>".
constexpr std::size_t kMaxMessage = 1 << 20;

bool send_message(int socket, const std::string& text) {
  return ::send(socket, text.data(), text.size(), MSG_NOSIGNAL) ==
         static_cast<ssize_t>(text.size());
}

/// The next message, or false when the other side is gone.
bool receive_message(int socket, std::string& text) {
  text.resize(kMaxMessage);
  ssize_t n;
  do {
    n = ::recv(socket, text.data(), text.size(), 0);
  } while (n < 0 && errno == EINTR);
  if (n <= 0) return false;
  text.resize(static_cast<std::size_t>(n));
  return true;
}

/// The server's loop, in the forked server process; never returns.
[[noreturn]] void serve(int socket, pid_t rank,
                        const std::function<int(const std::vector<std::string>&)>& run,
                        bool load_image_module) {
  end_with_parent(rank);
  // The rank blocks the interrupt signals for its signal thread, which is not here: the server
  // ends by them; its children block them again for their own (run_cli_in_forked_child).
  sigset_t blocked, none;
  sigemptyset(&none);
  pthread_sigmask(SIG_SETMASK, &none, &blocked);
  bool image_module = false;
  if (load_image_module) {
    // Before the first request, while the rank is in MPI_Init (about half a second here, which
    // the first point waited for after MPI's start-up).
    preload_image_module();
    image_module = true;
  }
  std::string request;
  while (receive_message(socket, request)) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (start < request.size()) {
      const std::size_t end = request.find('\0', start);
      if (end == std::string::npos) break;
      parts.push_back(request.substr(start, end - start));
      start = end + 1;
    }
    if (parts.size() < 2) {
      send_message(socket, "E a malformed request");
      continue;
    }
    const int log = ::open(parts[0].c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (log < 0) {
      send_message(socket, "E cannot write " + parts[0] + ": " + std::strerror(errno));
      continue;
    }
    std::vector<std::string> args(parts.begin() + 1, parts.end());
    // The image library once, for every later child, when the first run that writes an image
    // comes (a timing-only sweep never loads it).
    if (!image_module && writes_image(args)) {
      preload_image_module();
      image_module = true;
    }
    const pid_t pid = runs::fork_logged(log, args, run, [&] {
      pthread_sigmask(SIG_SETMASK, &blocked, nullptr);
      ::close(socket);
    });
    ::close(log);
    if (pid < 0) {
      send_message(socket, std::string("E fork: ") + std::strerror(errno));
      continue;
    }
    send_message(socket, "P " + std::to_string(pid));
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    send_message(socket, "S " + std::to_string(status));
  }
  std::_Exit(0);
}

}  // namespace

ForkServers::ForkServers(int count, std::function<int(const std::vector<std::string>&)> run,
                         bool load_image_module) {
  const pid_t rank = ::getpid();
  for (int i = 0; i < count; ++i) {
    int pair[2];
    if (::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, pair) != 0)
      throw std::runtime_error(std::string("fork server: socketpair: ") + std::strerror(errno));
    std::cout.flush();
    std::cerr.flush();
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::close(pair[0]);
      for (const auto& s : servers_) ::close(s.socket);  // the other servers' ends
      serve(pair[1], rank, run, load_image_module);
    }
    ::close(pair[1]);
    if (pid < 0) {
      ::close(pair[0]);
      throw std::runtime_error(std::string("fork server: fork: ") + std::strerror(errno));
    }
    servers_.push_back({pid, pair[0], false});
  }
}

ForkServers::~ForkServers() {
  for (auto& s : servers_) {
    ::close(s.socket);
    int status = 0;
    while (::waitpid(s.pid, &status, 0) < 0 && errno == EINTR) {
    }
  }
}

int ForkServers::run_and_wait(const std::vector<std::string>& args,
                              const std::filesystem::path& log,
                              const std::function<void(pid_t)>& started, std::string& error) {
  Server* server = nullptr;
  {
    std::unique_lock lock(mutex_);
    free_.wait(lock, [this] {
      for (const auto& s : servers_)
        if (!s.busy) return true;
      return false;
    });
    for (auto& s : servers_)
      if (!s.busy) {
        server = &s;
        break;
      }
    server->busy = true;
  }
  const auto release = [&] {
    {
      std::lock_guard lock(mutex_);
      server->busy = false;
    }
    free_.notify_one();
  };
  std::string request = log.string() + '\0';
  for (const auto& a : args) request += a + '\0';
  std::string reply;
  if (!send_message(server->socket, request) || !receive_message(server->socket, reply)) {
    error = "the fork server (pid " + std::to_string(server->pid) + ") is gone";
    release();
    return -1;
  }
  if (reply.rfind("E ", 0) == 0) {
    error = reply.substr(2);
    release();
    return -1;
  }
  started(static_cast<pid_t>(std::atol(reply.c_str() + 2)));
  if (!receive_message(server->socket, reply) || reply.rfind("S ", 0) != 0) {
    error = "the fork server (pid " + std::to_string(server->pid) + ") ended during the run";
    release();
    return -1;
  }
  release();
  return std::atoi(reply.c_str() + 2);
}

std::function<int(const std::vector<std::string>&, const std::filesystem::path&,
                  const std::function<void(pid_t)>&, std::string&)>
fork_server_runner(ForkServers& servers) {
  return [&servers](const std::vector<std::string>& args, const std::filesystem::path& log,
                    const std::function<void(pid_t)>& started,
                    std::string& error) { return servers.run_and_wait(args, log, started, error); };
}

}  // namespace rtsim::app
