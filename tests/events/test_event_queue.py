"""EventQueue semantics: queued devices, state, tie, noise, timers, script timing."""

import pytest

from vgxsim.events import AUTO_QUEUED, EventQueue, EventSource, ScriptExhausted, Step

# Device numbers (SGI device.h), local so these tests do not need vgxsim.DEVICE.
ESCKEY, AKEY, LEFTSHIFTKEY = 7, 11, 6
RIGHTMOUSE, MIDDLEMOUSE, LEFTMOUSE = 101, 102, 103
MOUSEX, MOUSEY, DIAL0 = 266, 267, 257
KEYBD, TIMER0, TIMER1 = 513, 515, 516
REDRAW, INPUTCHANGE, WINQUIT, DEPTHCHANGE, WINSHUT = 528, 534, 542, 543, 546


def drain(q):
    out = []
    while q.qtest():
        out.append(q.qread())
    return out


def test_unqueued_devices_are_dropped_but_update_state():
    q = EventQueue()
    q.post(LEFTMOUSE, 1)
    q.post(MOUSEX, 100)
    q.post(KEYBD, ord("a"))
    assert len(q) == 0 and q.qtest() == 0
    assert q.getbutton(LEFTMOUSE) == 1
    assert q.getvaluator(MOUSEX) == 100


def test_queued_devices_enter_in_order():
    q = EventQueue()
    for dev in (LEFTMOUSE, MOUSEX, KEYBD):
        q.qdevice(dev)
    q.post(LEFTMOUSE, 1)
    q.post(MOUSEY, 5)  # not queued
    q.post(MOUSEX, 7)
    q.post(KEYBD, 97)
    assert q.isqueued(LEFTMOUSE) == 1 and q.isqueued(MOUSEY) == 0
    assert q.qtest() == LEFTMOUSE
    assert drain(q) == [(LEFTMOUSE, 1), (MOUSEX, 7), (KEYBD, 97)]
    q.unqdevice(LEFTMOUSE)
    q.post(LEFTMOUSE, 0)
    assert len(q) == 0 and q.getbutton(LEFTMOUSE) == 0


def test_unqdevice_keeps_existing_entries():
    q = EventQueue()
    q.qdevice(ESCKEY)
    q.post(ESCKEY, 1)
    q.unqdevice(ESCKEY)
    assert q.qread() == (ESCKEY, 1)


def test_qread_returns_tuple_and_qtest_does_not_remove():
    q = EventQueue()
    q.qenter(REDRAW, 1)
    assert q.qtest() == REDRAW
    assert q.qtest() == REDRAW
    ev = q.qread()
    assert ev == (REDRAW, 1) and isinstance(ev, tuple)
    assert q.qtest() == 0


def test_qenter_bypasses_queued_set_and_state():
    q = EventQueue()
    q.qenter(LEFTMOUSE, 1)
    assert q.qread() == (LEFTMOUSE, 1)
    assert q.getbutton(LEFTMOUSE) == 0


def test_values_are_c_shorts():
    q = EventQueue()
    q.qenter(REDRAW, 0x18000)
    assert q.qread() == (REDRAW, -32768)


def test_qreset_empties_queue_only():
    q = EventQueue(EventSource.from_events([(ESCKEY, 1)]))
    q.qdevice(ESCKEY)
    q.qenter(REDRAW, 1)
    q.qenter(REDRAW, 2)
    q.qreset()
    assert len(q) == 0
    assert q.qread() == (ESCKEY, 1)  # script input survives a qreset


def test_device_numbers_must_be_ints():
    q = EventQueue()
    with pytest.raises(TypeError):
        q.qdevice(7.0)
    with pytest.raises(TypeError):
        q.qenter(REDRAW, 1.5)


def test_window_opened_queues_window_devices_and_redraw():
    q = EventQueue()
    q.window_opened(3)
    assert AUTO_QUEUED == (REDRAW, INPUTCHANGE, WINQUIT, WINSHUT, DEPTHCHANGE)
    assert all(q.isqueued(d) for d in AUTO_QUEUED)
    assert q.qread() == (REDRAW, 3)
    q.post(WINQUIT, 3)
    assert q.qread() == (WINQUIT, 3)


def test_getbutton_state_tracks_press_and_release():
    q = EventQueue()
    assert q.getbutton(AKEY) == 0
    q.post(AKEY, 1)
    assert q.getbutton(AKEY) == 1
    q.post(AKEY, 0)
    assert q.getbutton(AKEY) == 0
    assert q.getbutton(MOUSEX) == 0  # not a button
    assert q.getvaluator(DIAL0) == 0


def test_tie_appends_valuators_after_button():
    q = EventQueue()
    q.qdevice(LEFTMOUSE)
    q.tie(LEFTMOUSE, MOUSEX, MOUSEY)
    q.post(MOUSEX, 10)
    q.post(MOUSEY, 20)
    q.post(LEFTMOUSE, 1)
    assert drain(q) == [(LEFTMOUSE, 1), (MOUSEX, 10), (MOUSEY, 20)]
    q.tie(LEFTMOUSE, MOUSEY, 0)
    q.post(LEFTMOUSE, 0)
    assert drain(q) == [(LEFTMOUSE, 0), (MOUSEY, 20)]
    q.tie(LEFTMOUSE, 0, 0)
    q.post(LEFTMOUSE, 1)
    assert drain(q) == [(LEFTMOUSE, 1)]


def test_tie_needs_a_queued_button():
    q = EventQueue()
    q.tie(LEFTMOUSE, MOUSEX, MOUSEY)
    q.post(LEFTMOUSE, 1)
    assert len(q) == 0


def test_tie_rejects_wrong_device_kinds():
    q = EventQueue()
    with pytest.raises(ValueError):
        q.tie(MOUSEX, MOUSEY, 0)
    with pytest.raises(ValueError):
        q.tie(LEFTMOUSE, KEYBD, 0)


def test_valuator_entries_only_on_change():
    q = EventQueue()
    q.qdevice(MOUSEX)
    q.post(MOUSEX, 0)  # same as the initial value
    q.post(MOUSEX, 3)
    q.post(MOUSEX, 3)
    assert drain(q) == [(MOUSEX, 3)]


def test_noise_filters_small_valuator_moves():
    q = EventQueue()
    q.qdevice(MOUSEX)
    q.noise(MOUSEX, 5)
    for x in (2, 4, 5, 7, 9, 10, 16):
        q.post(MOUSEX, x)
    assert drain(q) == [(MOUSEX, 5), (MOUSEX, 10), (MOUSEX, 16)]
    assert q.getvaluator(MOUSEX) == 16
    q.post(MOUSEX, 12)  # state follows every change, entries do not
    assert q.getvaluator(MOUSEX) == 12 and len(q) == 0


def test_timers_tick_once_per_frame_with_noise_divisor():
    q = EventQueue(EventSource([Step(after=100)]))
    q.qdevice(TIMER0)
    q.qdevice(TIMER1)
    q.noise(TIMER1, 3)
    for _ in range(6):
        q.frame_done()
    evs = drain(q)
    assert evs.count((TIMER0, 0)) == 6
    assert evs.count((TIMER1, 0)) == 2
    assert q.frame == 6 and q.ticks == 6


def test_unqueued_timer_makes_no_entries():
    q = EventQueue()
    q.frame_done()
    q.tick(5)
    assert len(q) == 0


def test_script_exhausted_on_blocking_read():
    q = EventQueue(EventSource.from_events([(ESCKEY, 1)]))
    q.qdevice(ESCKEY)
    assert q.qread() == (ESCKEY, 1)
    with pytest.raises(ScriptExhausted) as info:
        q.qread()
    assert info.value.reason == "exhausted"


def test_script_exhausted_is_not_an_exception():
    assert issubclass(ScriptExhausted, BaseException)
    assert not issubclass(ScriptExhausted, Exception)
    q = EventQueue()
    with pytest.raises(ScriptExhausted):
        try:
            q.qread()
        except Exception:  # a program's catch-all must not swallow the end of the run
            pytest.fail("ScriptExhausted was caught by 'except Exception'")


def test_qtest_never_raises_when_exhausted():
    q = EventQueue()
    assert q.qtest() == 0


def test_unqueued_script_events_are_consumed_while_blocking():
    src = EventSource.from_events([(MOUSEX, 5), (MOUSEY, 6), (ESCKEY, 1)])
    q = EventQueue(src)
    q.qdevice(ESCKEY)
    assert q.qread() == (ESCKEY, 1)
    assert (q.getvaluator(MOUSEX), q.getvaluator(MOUSEY)) == (5, 6)


def test_after_delays_until_frame():
    src = EventSource()
    src.add((LEFTMOUSE, 1), after=2)
    q = EventQueue(src)
    q.qdevice(LEFTMOUSE)
    assert q.qtest() == 0  # not due at frame 0
    q.frame_done()
    assert q.qtest() == 0
    q.frame_done()  # frame 2: delivered by frame_done
    assert q.getbutton(LEFTMOUSE) == 1
    assert q.qread() == (LEFTMOUSE, 1)


def test_frame_done_delivers_one_step_per_frame_for_polling():
    src = EventSource.from_events([(LEFTMOUSE, 1), (MOUSEX, 10), (MOUSEX, 20), (LEFTMOUSE, 0)])
    q = EventQueue(src)
    seen = []
    for _ in range(4):
        q.frame_done()
        seen.append((q.getbutton(LEFTMOUSE), q.getvaluator(MOUSEX)))
    assert seen == [(1, 0), (1, 10), (1, 20), (0, 20)]


def test_wait_is_relative_to_previous_step():
    src = EventSource()
    src.add((LEFTMOUSE, 1))
    src.add((LEFTMOUSE, 0), wait=3)
    q = EventQueue(src)
    q.qdevice(LEFTMOUSE)
    q.qtest()  # delivers the press at frame 0
    states = []
    for _ in range(4):
        q.frame_done()
        states.append(q.getbutton(LEFTMOUSE))
    assert states == [1, 1, 0, 0]


def test_blocking_read_skips_delay_without_timers():
    src = EventSource()
    src.add((ESCKEY, 1), after=50)
    q = EventQueue(src)
    q.qdevice(ESCKEY)
    assert q.qread() == (ESCKEY, 1)
    assert q.frame == 0


def test_blocking_read_lets_timers_run_until_delay_passes():
    # mclock-style: redraw on every TIMER0 entry, one entry per 60 ticks.
    src = EventSource()
    src.add((ESCKEY, 1), after=3)
    q = EventQueue(src)
    q.window_opened(1)
    q.qdevice(ESCKEY)
    q.qdevice(TIMER0)
    q.noise(TIMER0, 60)
    seen = []
    while True:
        dev, _ = q.qread()
        seen.append(dev)
        if dev == ESCKEY:
            break
        if dev in (REDRAW, TIMER0):
            q.frame_done()  # the program redraws and swaps
    assert seen[0] == REDRAW
    assert seen[-1] == ESCKEY
    assert q.frame == 3
    assert seen.count(TIMER0) == 2


def test_idle_ticks_are_bounded():
    src = EventSource()
    src.add((ESCKEY, 1), after=5)
    q = EventQueue(src, max_idle_ticks=10)
    q.qdevice(ESCKEY)
    q.qdevice(TIMER0)
    evs = []
    while True:  # a program that never swaps: the delay is eventually skipped
        ev = q.qread()
        evs.append(ev)
        if ev[0] == ESCKEY:
            break
    assert evs.count((TIMER0, 0)) == 10


def test_script_ticks_step():
    src = EventSource()
    src.add(ticks=4)
    q = EventQueue(src)
    q.qdevice(TIMER0)
    q.noise(TIMER0, 2)
    assert q.qread() == (TIMER0, 0)
    assert q.qread() == (TIMER0, 0)
    with pytest.raises(ScriptExhausted):
        q.qread()


def test_stop_step_and_max_frames():
    src = EventSource()
    src.add(stop=True, after=2)
    q = EventQueue(src)
    q.frame_done()
    with pytest.raises(ScriptExhausted) as info:
        q.frame_done()
    assert info.value.reason == "stop" and info.value.frame == 2

    q = EventQueue(max_frames=3)
    q.frame_done()
    q.frame_done()
    with pytest.raises(ScriptExhausted) as info:
        q.frame_done()
    assert info.value.reason == "max_frames"


def test_many_ticks_at_once_are_counted_not_looped():
    from vgxsim.events.queue import MAX_TIMER_BACKLOG

    q = EventQueue()
    q.qdevice(TIMER0)
    q.qdevice(TIMER1)
    q.noise(TIMER1, 7)
    q.tick(3)  # TIMER1: 3 of its 7
    q.tick(1_000_000_000)  # one step, whatever the count
    assert q.ticks == 1_000_000_003
    evs = drain(q)
    # TIMER0 came due a billion times and TIMER1 (3 + 1e9) // 7 times: each capped
    assert evs.count((TIMER0, 0)) == 3 + MAX_TIMER_BACKLOG
    assert evs.count((TIMER1, 0)) == MAX_TIMER_BACKLOG
    # the phase is kept: 1000000003 = 7 * 142857143 + 2, so TIMER1 is 2 ticks into its
    # period and comes due again 5 ticks later
    q.tick(4)
    assert drain(q).count((TIMER1, 0)) == 0
    q.tick(1)
    assert drain(q).count((TIMER1, 0)) == 1


def test_tick_counts_exactly_below_the_backlog():
    q = EventQueue()
    q.qdevice(TIMER0)
    q.noise(TIMER0, 3)
    q.tick(2)
    assert len(q) == 0
    q.tick(10)  # ticks 3, 6, 9, 12
    assert drain(q) == [(TIMER0, 0)] * 4
    q.tick(0)
    assert q.ticks == 12
