// The fibre-optic network chapter's example networks, running on the ring simulator: the BASIC programs are
// C++ written line by line after the manual's, the operator's key presses are scripted.
// Host side (std::function, std::string); shared by `trionet ring simulate`, the examples and the tests.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "basic_program.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace trionet::examples {

using mc_node = ring::motion_coordinator<>;
using keypad_node = ring::keypad<>;
using trace_fn = std::function<void(const ring::link_byte&)>;

/// Presses and releases a key, then lets the ring run until it is quiet again.
template <class Scenario>
ring::key_status press(Scenario& s, keypad_node& keypad, ring::key k, const trace_fn& trace) {
  const ring::key_status result = keypad.press(k);
  (void)keypad.release(k);
  s.settle(trace);
  return result;
}

/// The keypad display as a 2 x 20 box.
inline std::string draw_display(const ring::keypad_display& display) {
  std::string box = "+--------------------+\n";
  for (std::size_t row = 0; row < ring::keypad_display::rows; ++row) {
    box += '|';
    box += display.line(row);
    box += "|\n";
  }
  box += "+--------------------+\n";
  return box;
}

// ---------------------------------------------------------------------------------------------------------
// Example 1: one Motion Coordinator and two keypads, one at each end of a 30 m machine.
//   ring: MC -> keypad 1 -> keypad 2 -> MC
struct example1 {
  vr_table<1024> vr;
  mc_node mc{vr};
  keypad_node keypad1, keypad2;
  ring::simulator<> sim;
  basic::program program;
  double length = 0, k = 0, a = 0;

  static constexpr const char* node_names[3] = {"MC", "keypad 1", "keypad 2"};

  example1() {
    (void)sim.add(mc);
    (void)sim.add(keypad1);
    (void)sim.add(keypad2);
    using namespace basic;
    auto& p = program;
    p.line([&] {
      length = 2;
      return next();
    });                                                      // length=2
    p.line([&] { return send_keypad_offset(mc, 10, 11); });  // SEND(10,2,11)
    p.line([&] { return send_keypad_offset(mc, 11, 10); });  // SEND(11,2,10)
    p.line([&] {
      return print(mc, 10, chr(12) + chr(14) + chr(20) + crlf);
    });  // PRINT #10,CHR(12);CHR(14);CHR(20)
    p.line([&] {
      return print(mc, 11, chr(12) + chr(14) + chr(20) + crlf);
    });                                                       // PRINT #11,CHR(12);CHR(14);CHR(20)
    p.line([&] { return print(mc, 10, "SPEED:" + crlf); });   // PRINT #10,"SPEED:":
    p.line([&] { return print(mc, 10, "LENGTH:" + crlf); });  //   PRINT #10,"LENGTH:"
    p.line([&] { return print(mc, 11, "SPEED:" + crlf); });   // PRINT #11,"SPEED:":
    p.line([&] { return print(mc, 11, "LENGTH:" + crlf); });  //   PRINT #11,"LENGTH:"
    p.line("repeat",
           [&] { return mc.key(3) ? gosub("read_key") : gosub("do_motion"); });  // IF KEY#3 THEN ...
    p.line([&] { return go_to("repeat"); });                                     // UNTIL FALSE
    p.line("read_key", [&] { return get(mc, 3, k); });                           // GET #3,k
    p.line([&] { return k > 9 ? go_to("not_num") : next(); });                   // IF k>9 THEN GOTO not_num
    p.line([&] {
      a = a * 10 + k;
      return next();
    });  // a=a*10+k
    p.line([&] {
      if (a > 9999) a = 0;
      return next();
    });  // IF a>9999 THEN a=0
    p.line([&] { return print(mc, 10, chr(27) + chr(72) + chr(7) + number(a, 6, 0) + crlf); });
    p.line([&] { return print(mc, 11, chr(27) + chr(72) + chr(7) + number(a, 6, 0) + crlf); });
    p.line("not_num", [&] {  // IF (k=10)&(VR(length)<10000)
      if (k == 10 && vr[vr_index()] < 10000) vr[vr_index()] = vr[vr_index()] + 0.1;
      return next();
    });
    p.line([&] {  // IF (k=11)&(VR(length)>0.1)
      if (k == 11 && vr[vr_index()] > 0.1) vr[vr_index()] = vr[vr_index()] - 0.1;
      return next();
    });
    p.line([&] { return print(mc, 10, cursor(28) + number(vr[vr_index()], 8, 1) + crlf); });
    p.line([&] { return print(mc, 11, cursor(28) + number(vr[vr_index()], 8, 1) + crlf); });
    p.line([&] { return ret(); });               // RETURN
    p.line("do_motion", [&] { return ret(); });  // main motion routine
  }

  std::size_t vr_index() const { return static_cast<std::size_t>(length); }

  /// One byte-time: the program runs, then the ring moves one byte per link.
  void tick(const trace_fn& trace) {
    program.run();
    sim.step(trace);
  }
  /// Runs until nothing is left to send and the program waits for a key (at most `limit` byte-times).
  void settle(const trace_fn& trace, std::uint64_t limit = 20000) {
    for (std::uint64_t t = 0; t < limit; ++t) {
      tick(trace);
      if (sim.quiet() && mc.characters_waiting() == 0 && t > 4) return;
    }
  }
};

// ---------------------------------------------------------------------------------------------------------
// Example 2: two Motion Coordinators and one keypad. The three-axis node is the master and reads the keypad;
// it hands the feed length and speed to the two-axis node.
//   ring: three-axis MC -> two-axis MC -> keypad -> three-axis MC
struct example2 {
  vr_table<1024> vr_three, vr_two;
  mc_node three_axis{vr_three}, two_axis{vr_two};
  keypad_node keypad;
  ring::simulator<> sim;
  basic::program three_axis_program, two_axis_program;
  double speed = 0;  // SPEED on the two-axis node

  static constexpr const char* node_names[3] = {"3-axis MC", "2-axis MC", "keypad"};

  example2() {
    (void)sim.add(three_axis);
    (void)sim.add(two_axis);
    (void)sim.add(keypad);
    using namespace basic;
    auto& vr = vr_three;
    auto& mc = three_axis;
    auto& p = three_axis_program;
    p.line("init", [&] { return send_keypad_offset(mc, 11, 10); });  // SEND(11,2,10)
    p.line([&] { return print(mc, 11, chr(12) + chr(14) + "INITIALISING....." + crlf); });
    p.line([&] { return print(mc, 10, "I"); });               // PRINT #10,"I";
    p.line([&] { return next(); });                           // GOSUB initax
    p.line([&] { return vr[200] == 99 ? next() : wait(); });  // WAIT UNTIL VR(200)=99
    p.line([&] { return print(mc, 11, chr(12) + chr(14) + "MACHINE READY" + crlf); });
    p.line("setlen", [&] { return print(mc, 11, "FEED LENGTH:" + number(vr[0], 6, 1)); });
    p.line([&] { return get(mc, 3, vr[100]); });                      // GET #3,VR(100)
    p.line([&] { return vr[100] == 13 ? go_to("setsp") : next(); });  // IF VR(100)=13 THEN GOTO setsp
    p.line([&] {                                                      // IF (VR(100)=10)AND(VR(0)<1000000)
      if (vr[100] == 10 && vr[0] < 1000000) vr[0] = vr[0] + 0.1;
      return next();
    });
    p.line([&] {  // IF (VR(100)=11)AND(VR(0)>0.1)
      if (vr[100] == 11 && vr[0] > 0.1) vr[0] = vr[0] - 0.1;
      return next();
    });
    p.line([&] { return print(mc, 11, chr(27) + chr(72) + chr(32) + number(vr[0], 6, 1)); });
    p.line([&] { return go_to("setlen"); });  // GOTO setlen
    p.line("setsp",
           [&] { return print(mc, 11, "SPEED:" + number(vr[1], 0, 2)); });  // PRINT #11,"SPEED:";VR(1)[2];
    p.line([&] { return get(mc, 3, vr[100]); });                            // GET #3,VR(100)
    p.line([&] { return vr[100] == 13 ? go_to("initnet") : next(); });      // IF VR(100)=13 THEN GOTO initnet
    p.line([&] {                                                            // IF (VR(100)=10)AND(VR(1)<100)
      if (vr[100] == 10 && vr[1] < 100) vr[1] = vr[1] + 0.01;
      return next();
    });
    p.line([&] {  // IF (VR(100)=11)AND(VR(1)>0.01)
      if (vr[100] == 11 && vr[1] > 0.01) vr[1] = vr[1] - 0.01;
      return next();
    });
    p.line([&] { return print(mc, 11, chr(27) + chr(72) + chr(46) + number(vr[1], 0, 2)); });
    p.line([&] { return go_to("setsp"); });                              // GOTO setsp
    p.line("initnet", [&] { return send_variable(mc, 10, 0, vr[0]); });  // SEND(10,1,0,VR(0))
    p.line([&] { return send_variable(mc, 10, 1, vr[1]); });             // SEND(10,1,1,VR(1))
    p.line("start", [&] { return print(mc, 11, chr(12) + chr(14) + "PRESS START TO RUN" + crlf); });
    p.line("readkey", [&] { return mc.key(3) ? next() : wait(); });     // WAIT UNTIL KEY#3
    p.line([&] { return get(mc, 3, vr[100]); });                        // GET #3,VR(100)
    p.line([&] { return vr[100] != 20 ? go_to("readkey") : next(); });  // IF VR(100)<>20 THEN GOTO readkey
    p.line([&] { return print(mc, 10, "G"); });                         // PRINT #10,"G";
    p.line([&] { return vr[200] == 999 ? next() : wait(); });           // WAIT UNTIL VR(200)=999
    p.line("moves", [&] { return wait(); });                            // main motion routine

    auto& vr2 = vr_two;
    auto& mc2 = two_axis;
    auto& q = two_axis_program;
    q.line("readinit",
           [&] { return !mc2.key(4) ? go_to("readinit") : next(); });     // IF NOT(KEY#4) THEN GOTO readinit
    q.line([&] { return get(mc2, 4, vr2[100]); });                        // GET #4, VR(100)
    q.line([&] { return vr2[100] != 73 ? go_to("readinit") : next(); });  // IF VR(100)<>73 THEN GOTO readinit
    q.line([&] { return next(); });                                       // GOSUB initax
    q.line([&] { return send_variable(mc2, 11, 200, 99); });              // SEND(11,1,200,99)
    q.line("readsp",
           [&] { return !mc2.key(4) ? go_to("readsp") : next(); });  // IF NOT(KEY#4) THEN GOTO readsp
    q.line([&] {
      speed = vr2[1];
      return next();
    });                                                                 // SPEED=VR(1)
    q.line([&] { return get(mc2, 4, vr2[100]); });                      // GET#4,VR(100)
    q.line([&] { return vr2[100] != 71 ? go_to("readsp") : next(); });  // IF VR(100)<>71 THEN GOTO readsp
    q.line([&] { return send_variable(mc2, 11, 200, 999); });           // SEND(11,1,200,999)
    q.line("moves", [&] { return wait(); });                            // main motion routine
  }

  void tick(const trace_fn& trace) {
    three_axis_program.run();
    two_axis_program.run();
    sim.step(trace);
  }
  void settle(const trace_fn& trace, std::uint64_t limit = 20000) {
    for (std::uint64_t t = 0; t < limit; ++t) {
      tick(trace);
      if (sim.quiet() && three_axis.characters_waiting() == 0 && two_axis.characters_waiting() == 0 && t > 4)
        return;
    }
  }
  /// Runs until `done()` or `limit` byte-times; true if `done()` came true.
  bool run_until(const std::function<bool()>& done, const trace_fn& trace, std::uint64_t limit = 100000) {
    for (std::uint64_t t = 0; t < limit; ++t) {
      if (done()) return true;
      tick(trace);
    }
    return done();
  }

  /// The operator's session: wait for MACHINE READY, feed length up 3 x 0.1, enter, speed up 2 x 0.01,
  /// enter, then START. `phase(text)` is called at each stage (for a demo's commentary).
  bool operate(const trace_fn& trace, const std::function<void(const std::string&)>& phase) {
    if (!run_until([&] { return vr_three[200] == 99 && three_axis_program.where() == "setlen"; }, trace))
      return false;
    settle(trace);
    phase("two-axis node answered \"I\" with VR(200)=99; keypad asks for the feed length");
    for (int i = 0; i < 3; ++i) press(*this, keypad, ring::key::up, trace);
    press(*this, keypad, ring::key::yes, trace);
    phase("feed length set with up x 3 and Y; keypad asks for the speed");
    for (int i = 0; i < 2; ++i) press(*this, keypad, ring::key::up, trace);
    press(*this, keypad, ring::key::yes, trace);
    settle(trace);
    phase("speed set with up x 2 and Y; parameters sent to the two-axis node");
    press(*this, keypad, ring::key::start, trace);
    const bool ran = run_until([&] { return vr_three[200] == 999; }, trace);
    settle(trace);
    phase("START pressed: \"G\" sent, two-axis node answered VR(200)=999");
    return ran;
  }
};

}  // namespace trionet::examples
