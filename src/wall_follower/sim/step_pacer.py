"""When the simulator may take its next world step.

Real `stageros -g` steps as fast as the CPU allows, so Python controllers,
which answer each scan a little later, fall behind and see the world jump.
The built-in simulator instead holds a chosen multiple of real time, gives a
controller whose answer is a little late part of a period more (the steady
schedule takes the delay back on the next steps), and can go further and
wait for the controllers (lockstep), which makes a robot's driving the same
however busy the machine is, short of the timeout. Only while nobody drives
does the world step by the wall clock (the grace), so how long a robot
stands before it first moves can differ by a step from run to run.
"""
import threading
import time


class StepPacer(object):
    """Paces world steps for the simulator's main loop.

    period: wall seconds between steps (interval_sim / speedup); 0 steps as
        fast as possible.
    patience: without lockstep, how long past its time a step waits for a
        new command from every robot that is being driven (wall seconds).
    lockstep: before each step, wait for a new command from every robot that
        is being driven, at most `timeout` wall seconds (so a controller that
        died cannot freeze the world); when nobody drives, wait at most
        `grace` for someone to start.

    Command callbacks call command_arrived() from their own threads; the main
    loop calls wait_turn() before each step and readings_out() as the step's
    readings go out. In lockstep only a command that comes after them
    answers them: one that came while the step was computed answers the
    readings before (from a controller a step behind: at its start, or
    after a step the timeout let go), and taken for the answer to these it
    let the world step before they were answered, and kept every answer
    after it a step late.
    """

    STOP_POLL = 0.1

    def __init__(self, period, robot_count=1, lockstep=False, grace=0.05, timeout=1.0,
                 patience=0.0, clock=time.monotonic):
        self.period = max(0.0, period)
        self.patience = max(0.0, patience)
        self.lockstep = lockstep
        self.grace = grace
        self.timeout = timeout
        self._clock = clock
        self._due = None
        self._fresh = [False] * robot_count
        self._out_at = None   # clock() when the newest readings went out
        self._stopped = False
        self._condition = threading.Condition()

    def now(self):
        """The pacer's clock, for timing a command before it can be handed on."""
        return self._clock()

    def command_arrived(self, index, at=None):
        """Robot index's command came at time `at` by now() (now by default)."""
        at = self._clock() if at is None else at
        with self._condition:
            if self._out_at is None or at >= self._out_at:
                self._fresh[index] = True
                self._condition.notify_all()

    def readings_out(self):
        """The step's readings are going out: only a command that comes from now on
        answers them."""
        with self._condition:
            self._out_at = self._clock()
            self._fresh = [False] * len(self._fresh)

    def stop(self):
        """Releases a waiting wait_turn(), which then returns False."""
        with self._condition:
            self._stopped = True
            self._condition.notify_all()

    @property
    def stopped(self):
        return self._stopped

    def request_stop(self):
        """stop() for a signal handler: it takes no lock, because the thread
        it interrupts may hold one; a waiting wait_turn() notices within
        STOP_POLL seconds."""
        self._stopped = True

    def wait_turn(self, driving):
        """Blocks until the next step may start; False once stop() was called.

        driving[i] says whether robot i is being driven (Simulation.driven():
        commanded to move, or held still by a controller that answers every
        step), i.e. whether its next command is worth waiting for.
        """
        with self._condition:
            if self._due is not None:
                self._wait_until(self._due, lambda: False)
            if self.lockstep:
                self._wait_for_commands(driving, self.timeout, self.grace)
            elif self.patience > 0.0:
                self._wait_for_commands(driving, self.patience, 0.0)
            self._fresh = [False] * len(self._fresh)
            self._schedule_next(self._clock())
            return not self._stopped

    def _wait_for_commands(self, driving, timeout, grace):
        awaited = [index for index, active in enumerate(driving) if active]
        if awaited:
            self._wait_until(self._clock() + timeout,
                             lambda: all(self._fresh[index] for index in awaited))
        elif grace > 0.0:
            self._wait_until(self._clock() + grace, lambda: any(self._fresh))

    def _wait_until(self, deadline, ready):
        while not self._stopped and not ready():
            remaining = deadline - self._clock()
            if remaining <= 0.0:
                return
            self._condition.wait(min(remaining, self.STOP_POLL))

    def _schedule_next(self, start):
        """Keeps a steady schedule through small delays, but restarts it after
        falling a whole period behind: catching up in a burst of steps is
        exactly what starves the controllers.
        """
        if self.period <= 0.0:
            return
        on_time = self._due is not None and start - self._due < self.period
        self._due = (self._due if on_time else start) + self.period
