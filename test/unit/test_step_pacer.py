"""The simulator's step pacing: a held rate that never bursts, and lockstep.

Only lower bounds of wall time are asserted (a loaded machine can only make
things slower), and waits that should end early are given generous limits.
"""
import threading
import time

from wall_follower.sim.step_pacer import StepPacer


def run_steps(pacer, count, driving=(False,)):
    start = time.monotonic()
    for _ in range(count):
        assert pacer.wait_turn(list(driving))
    return time.monotonic() - start


def test_a_held_rate_is_never_exceeded():
    pacer = StepPacer(period=0.01)
    assert run_steps(pacer, 21) >= 0.2


def test_no_burst_after_falling_behind():
    # The late step starts at once and restarts the schedule from its own
    # start, so it and the three after it take at least three periods (a
    # burst would take none). The clock starts before the late step: started
    # after it, it would miss however long that step took after its schedule
    # was set, and a loaded machine would fail the test.
    pacer = StepPacer(period=0.02)
    pacer.wait_turn([False])
    time.sleep(0.1)                 # five periods late
    assert run_steps(pacer, 4) >= 0.06


def test_unpaced_steps_do_not_wait():
    pacer = StepPacer(period=0.0, lockstep=False)
    assert run_steps(pacer, 1000) < 5.0


def send_later(pacer, index, delay=0.05):
    """Start a timer that delivers robot index's command; returns its arrival times."""
    arrivals = []

    def send():
        arrivals.append(time.monotonic())
        pacer.command_arrived(index)
    sender = threading.Timer(delay, send)
    sender.start()
    return sender, arrivals


def test_lockstep_waits_for_the_driven_robot_and_no_longer():
    pacer = StepPacer(period=0.0, lockstep=True, timeout=30.0)
    sender, arrivals = send_later(pacer, 0)
    elapsed = run_steps(pacer, 1, driving=[True])
    stepped = time.monotonic()
    sender.join()
    assert stepped >= arrivals[0]
    assert elapsed < 20.0


def test_lockstep_steps_at_once_when_the_command_is_already_there():
    pacer = StepPacer(period=0.0, lockstep=True, timeout=30.0)
    pacer.command_arrived(0)
    assert run_steps(pacer, 1, driving=[True]) < 20.0


def test_lockstep_takes_no_command_from_before_the_readings_for_their_answer():
    # A controller a step behind answers the readings before while the step is
    # computed: the world waits for the answer to the readings that went out.
    pacer = StepPacer(period=0.0, lockstep=True, timeout=0.2)
    pacer.command_arrived(0)
    before = pacer.now()
    pacer.readings_out()
    pacer.command_arrived(0, at=before)   # came before, let in after (a step under way)
    assert run_steps(pacer, 1, driving=[True]) >= 0.2


def test_lockstep_takes_a_command_after_the_readings_for_their_answer():
    pacer = StepPacer(period=0.0, lockstep=True, timeout=30.0)
    pacer.readings_out()
    pacer.command_arrived(0)
    assert run_steps(pacer, 1, driving=[True]) < 20.0


def test_lockstep_gives_up_on_a_silent_controller_after_the_timeout():
    pacer = StepPacer(period=0.0, lockstep=True, timeout=0.05)
    assert run_steps(pacer, 2, driving=[True]) >= 0.1


def test_lockstep_waits_only_the_grace_when_nobody_drives():
    pacer = StepPacer(period=0.0, lockstep=True, grace=0.02, timeout=30.0)
    elapsed = run_steps(pacer, 3, driving=[False])
    assert 0.06 <= elapsed < 20.0


def test_lockstep_waits_for_every_driven_robot():
    pacer = StepPacer(period=0.0, robot_count=2, lockstep=True, timeout=30.0)
    pacer.command_arrived(0)
    sender, arrivals = send_later(pacer, 1)
    run_steps(pacer, 1, driving=[True, True])
    stepped = time.monotonic()
    sender.join()
    assert stepped >= arrivals[0]


def test_stop_releases_a_waiting_step():
    pacer = StepPacer(period=0.0, lockstep=True, timeout=30.0)
    stopper = threading.Timer(0.05, pacer.stop)
    stopper.start()
    assert pacer.wait_turn([True]) is False
    stopper.join()


def test_a_held_rate_waits_a_little_for_a_late_command():
    # The command comes 30 ms after the step's time; the step waits for it (patience 0.2 s).
    pacer = StepPacer(period=0.01, patience=0.2)
    pacer.wait_turn([True])
    sender, arrivals = send_later(pacer, 0, delay=0.03)
    assert pacer.wait_turn([True])
    stepped = time.monotonic()
    sender.join()
    assert stepped >= arrivals[0]


def test_a_held_rate_waits_no_longer_than_its_patience():
    pacer = StepPacer(period=0.01, patience=0.05)
    pacer.wait_turn([True])
    start = time.monotonic()
    assert pacer.wait_turn([True])   # no command ever comes
    assert time.monotonic() - start >= 0.05


def test_a_held_rate_waits_for_nobody_when_no_robot_is_driven():
    pacer = StepPacer(period=0.01, patience=30.0)
    assert run_steps(pacer, 5, driving=[False]) < 20.0
