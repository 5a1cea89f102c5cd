#pragma once
// A WebSocket client for the server's tests (Boost.Beast, blocking): connects offering one
// subprotocol, sends JSON, reads text and binary messages.

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

namespace comply::viewer::testing {

struct WsMessage {
  bool text = false;
  std::string data;
  [[nodiscard]] nlohmann::json json() const { return nlohmann::json::parse(data); }
  /// messageData: the subscription, the log time and the payload.
  [[nodiscard]] std::uint32_t subscription() const {
    std::uint32_t value = 0;
    for (int i = 3; i >= 0; --i) {
      value = (value << 8) | static_cast<std::uint8_t>(data[1 + i]);
    }
    return value;
  }
  [[nodiscard]] std::uint64_t logTime() const {
    std::uint64_t value = 0;
    for (int i = 7; i >= 0; --i) {
      value = (value << 8) | static_cast<std::uint8_t>(data[5 + i]);
    }
    return value;
  }
  [[nodiscard]] std::string payload() const { return data.substr(13); }
};

class WsTestClient {
 public:
  /// Throws boost::system::system_error when the handshake fails (a refused subprotocol).
  WsTestClient(std::uint16_t port, const std::string& subprotocol) : socket_(io_) {
    boost::asio::ip::tcp::resolver resolver(io_);
    boost::asio::connect(socket_.next_layer(), resolver.resolve("127.0.0.1", std::to_string(port)));
    socket_.set_option(boost::beast::websocket::stream_base::decorator(
        [subprotocol](boost::beast::websocket::request_type& request) {
          request.set(boost::beast::http::field::sec_websocket_protocol, subprotocol);
        }));
    boost::beast::websocket::response_type response;
    socket_.handshake(response, "127.0.0.1", "/");
    protocol_ = std::string(response[boost::beast::http::field::sec_websocket_protocol]);
  }

  [[nodiscard]] const std::string& protocol() const { return protocol_; }

  WsMessage read() {
    boost::beast::flat_buffer buffer;
    socket_.read(buffer);
    return {socket_.got_text(), boost::beast::buffers_to_string(buffer.data())};
  }

  /// The next text message (binary ones before it are skipped).
  nlohmann::json readJson() {
    for (;;) {
      const WsMessage message = read();
      if (message.text) {
        return message.json();
      }
    }
  }

  void send(const std::string& text) {
    socket_.text(true);
    socket_.write(boost::asio::buffer(text));
  }
  void sendBinary(const std::string& bytes) {
    socket_.binary(true);
    socket_.write(boost::asio::buffer(bytes));
  }
  void subscribe(std::uint32_t subscription, std::uint32_t channel) {
    send(nlohmann::json{{"op", "subscribe"},
                        {"subscriptions", {{{"id", subscription}, {"channelId", channel}}}}}
             .dump());
  }
  void close() { socket_.close(boost::beast::websocket::close_code::normal); }

 private:
  boost::asio::io_context io_;
  boost::beast::websocket::stream<boost::asio::ip::tcp::socket> socket_;
  std::string protocol_;
};

}  // namespace comply::viewer::testing
