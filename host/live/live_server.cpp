#include "live/live_server.hpp"

#include <csignal>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>
#include <httplib.h>

#include "live/live_page.hpp"

namespace vkrt::live {
namespace {

// A slow or hostile client holds a worker for at most this long, and never more
// than kWorkers of them: the page may wait, the render never does.
constexpr time_t kTimeoutSeconds = 2;
constexpr std::size_t kWorkers = 4;
constexpr std::size_t kMaxBody = 1024;  // no request of the page carries a body
constexpr std::size_t kMaxHeaders = 64;  // a browser sends about a dozen

const httplib::Headers kHeaders{
    {"Cache-Control", "no-store"},
    {"X-Content-Type-Options", "nosniff"},
    // The page loads nothing from anywhere else, and no other site may frame it.
    {"Content-Security-Policy",
     "default-src 'none'; img-src 'self'; connect-src 'self'; style-src 'unsafe-inline'; "
     "script-src 'unsafe-inline'; frame-ancestors 'none'"},
};

void serve_routes(httplib::Server& server, LiveFeed& feed) {
    server.set_pre_routing_handler([](const httplib::Request& req, httplib::Response& res) {
        if (req.headers.size() <= kMaxHeaders) return httplib::Server::HandlerResponse::Unhandled;
        res.status = 431;
        res.set_content("too many header fields\n", "text/plain");
        return httplib::Server::HandlerResponse::Handled;
    });
    server.Get("/", [](const httplib::Request&, httplib::Response& res) {
        res.set_content(std::string(kLivePage), "text/html; charset=utf-8");
    });
    // Browsers ask for it unbidden; answered so that they need not be told "not found".
    server.Get("/favicon.ico", [](const httplib::Request&, httplib::Response& res) { res.status = 204; });
    server.Get("/status", [&feed](const httplib::Request&, httplib::Response& res) {
        res.set_content(feed.status_json(), "application/json");
    });
    server.Get("/image.png", [&feed](const httplib::Request& req, httplib::Response& res) {
        std::uint64_t version = 0;
        const auto png = feed.png(version);
        if (!png) {
            res.status = 404;
            res.set_content("no image yet\n", "text/plain");
            return;
        }
        const std::string etag = fmt::format("\"{}\"", version);
        res.set_header("ETag", etag);
        if (req.get_header_value("If-None-Match") == etag) {
            res.status = 304;
            return;
        }
        res.set_content(reinterpret_cast<const char*>(png->data()), png->size(), "image/png");
    });
    // A custom header makes a cross-site form or fetch need a preflight, which is
    // never granted: only the page itself can stop the render.
    server.Post("/stop", [&feed](const httplib::Request& req, httplib::Response& res) {
        if (req.get_header_value("X-Vkrt-Stop") != "1") {
            res.status = 403;
            res.set_content("stop needs the header X-Vkrt-Stop: 1\n", "text/plain");
            return;
        }
        feed.request_stop();
        res.status = 202;
        res.set_content("stopping after this pass\n", "text/plain");
    });
    server.set_error_handler([](const httplib::Request&, httplib::Response& res) {
        if (res.body.empty()) res.set_content(fmt::format("error {}\n", res.status), "text/plain");
    });
    server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
        res.status = 500;
        res.set_content("500 internal error\n", "text/plain");
    });
}

}  // namespace

Endpoint parse_endpoint(const std::string& text) {
    Endpoint where;
    std::string port = text;
    if (const std::size_t colon = text.rfind(':'); colon != std::string::npos) {
        where.address = text.substr(0, colon);
        port = text.substr(colon + 1);
        if (where.address.size() >= 2 && where.address.front() == '[' && where.address.back() == ']') {
            where.address = where.address.substr(1, where.address.size() - 2);
        }
        if (where.address.empty()) throw std::invalid_argument(fmt::format("'{}': no address before the ':'", text));
    }
    if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos ||
        std::stoul(port) > 65535) {
        throw std::invalid_argument(fmt::format("'{}': expected [ADDRESS:]PORT with a port from 0 to 65535", text));
    }
    where.port = static_cast<std::uint16_t>(std::stoul(port));
    return where;
}

struct LiveServer::Impl {
    httplib::Server server;
    std::thread thread;
    std::string host;
    int port = 0;
};

LiveServer::LiveServer(LiveFeed& feed, const Endpoint& where) : impl_(std::make_unique<Impl>()) {
    // A browser that closes its connection mid-reply must not end the process.
    std::signal(SIGPIPE, SIG_IGN);
    httplib::Server& server = impl_->server;
    server.new_task_queue = [] { return new httplib::ThreadPool(kWorkers); };
    server.set_read_timeout(kTimeoutSeconds);
    server.set_write_timeout(kTimeoutSeconds);
    // One request a connection: a browser's idle keep-alive connection would hold a
    // worker, and the program's exit, for the whole keep-alive timeout.
    server.set_keep_alive_max_count(1);
    server.set_payload_max_length(kMaxBody);
    server.set_default_headers(kHeaders);
    serve_routes(server, feed);
    impl_->host = where.address;
    impl_->port = where.port == 0 ? server.bind_to_any_port(where.address)
                                  : (server.bind_to_port(where.address, where.port) ? where.port : -1);
    if (impl_->port <= 0) {
        throw std::runtime_error(fmt::format(
            "--serve {}:{}: cannot listen there (the port is in use, or the address is not one of this machine's)",
            where.address, where.port));
    }
    impl_->thread = std::thread([this] { impl_->server.listen_after_bind(); });
}

LiveServer::~LiveServer() {
    impl_->server.stop();
    if (impl_->thread.joinable()) impl_->thread.join();
}

std::string LiveServer::url() const {
    const bool v6 = impl_->host.find(':') != std::string::npos;
    return fmt::format("http://{}{}{}:{}/", v6 ? "[" : "", impl_->host, v6 ? "]" : "", impl_->port);
}

std::unique_ptr<LiveServer> serve_if_asked(LiveFeed& feed, const std::string& serve, const char* what) {
    if (serve.empty()) return nullptr;
    auto server = std::make_unique<LiveServer>(feed, parse_endpoint(serve));
    fmt::print(stderr, "live      {} shows {}\n", server->url(), what);
    return server;
}

}  // namespace vkrt::live
