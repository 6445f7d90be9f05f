#pragma once
// The live preview's web server (`vkrt render --serve`): one page, its status and
// its image, and a stop button, served from a thread of its own so that no request
// ever waits on the render or the render on a request. Nothing else is served: no
// file of the file system is reachable through it.
#include <cstdint>
#include <memory>
#include <string>

#include "live/live_feed.hpp"

namespace vkrt::live {

// Where to listen, from "[ADDRESS:]PORT" ("8080", "0.0.0.0:8080", "[::1]:8080").
// Port 0 picks a free port. Without an address, only this machine can connect.
struct Endpoint {
    std::string address = "127.0.0.1";
    std::uint16_t port = 0;
};

// Throws std::invalid_argument saying what is wrong with the text.
Endpoint parse_endpoint(const std::string& text);

class LiveServer {
public:
    // Listens at once, so a port in use is an error before any rendering.
    LiveServer(LiveFeed& feed, const Endpoint& where);
    ~LiveServer();  // stops serving; requests in progress are cut off
    LiveServer(const LiveServer&) = delete;
    LiveServer& operator=(const LiveServer&) = delete;

    std::string url() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// The server of a command's --serve option: none when `serve` is empty; else it
// listens at once (a port in use is refused before the slow work) and says where
// on standard error, `what` saying what the page shows.
std::unique_ptr<LiveServer> serve_if_asked(LiveFeed& feed, const std::string& serve, const char* what);

}  // namespace vkrt::live
