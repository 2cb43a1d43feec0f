#pragma once
// A third coupling scheme built in the test suite, to show what adding one takes: "hold", HELICS's
// default, where a domain's correction uses each partner's last value instead of an interpolation
// (tests/integration/hold_scheme_test.cpp runs it over threads and over processes).
namespace crashlink::test_schemes {

/// The two registration lines, one per side (daemon::register_domain_scheme,
/// coordinator::register_coordinator_scheme); once per process however often it is called.
void register_hold();

}  // namespace crashlink::test_schemes
