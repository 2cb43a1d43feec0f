#include "transport/failure.h"

#include <fmt/format.h>

#include <exception>
#include <filesystem>

#include "core/errors.h"
#include "core/exit_codes.h"
#include "transport/errors.h"

namespace crashlink::transport {

Failure current_failure() {
  try {
    throw;
  } catch (const StopRequested&) {
    return {kExitStopped, wire::ERROR_CODE_STOPPED, "stopped on request (signal)"};
  } catch (const PeerTimeoutError& e) {
    return {kExitPeer, wire::ERROR_CODE_TIMEOUT, e.what()};
  } catch (const TransportError& e) {
    return {kExitPeer, wire::ERROR_CODE_INTERNAL, e.what()};
  } catch (const ProtocolError& e) {
    return {kExitPeer, wire::ERROR_CODE_PROTOCOL, fmt::format("protocol error: {}", e.what())};
  } catch (const NumericalError& e) {
    return {kExitNumerical, wire::ERROR_CODE_NUMERICAL, e.what()};
  } catch (const IoError& e) {
    return {kExitIo, wire::ERROR_CODE_IO, fmt::format("I/O error: {}", e.what())};
  } catch (const std::filesystem::filesystem_error& e) {
    return {kExitIo, wire::ERROR_CODE_IO, fmt::format("I/O error: {}", e.what())};
  } catch (const InputError& e) {
    return {kExitInput, wire::ERROR_CODE_MODEL, fmt::format("input error: {}", e.what())};
  } catch (const ModelError& e) {
    return {kExitInput, wire::ERROR_CODE_MODEL, fmt::format("model error: {}", e.what())};
  } catch (const std::exception& e) {
    return {kExitInternal, wire::ERROR_CODE_INTERNAL, fmt::format("internal error: {}", e.what())};
  } catch (...) {
    return {kExitInternal, wire::ERROR_CODE_INTERNAL, "internal error: an unknown exception"};
  }
}

}  // namespace crashlink::transport
