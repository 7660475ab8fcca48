"""Runs replayed into a CommandLog as the simulators step them: what the grading tests feed it.

Shared by the unit tests (not itself a test module). Each step, stamped a
multiple of STEP, applies the latest command until the watchdog zeroes it,
and grading hears each command at a time of its own, late or in bursts as
on a busy machine.
"""
from wall_follower.evaluation.grading.commands import CommandLog

STEP = 0.1      # simulated s of a world step
WATCHDOG = 0.2  # simulated s
SIMULATORS = ('builtin', 'stageros')


def stage_log(commands, steps, simulator='builtin'):
    """A CommandLog of commands and of the velocity steps 1 .. steps applied.

    commands: (sent, heard, linear, angular), sent a step index (the clock
    read sent * STEP) and heard the simulated time grading heard it [s].
    A command drives the steps after it until the watchdog zeroes it: the
    built-in simulator zeroes it after the step that makes it WATCHDOG old,
    stageros before that step's odometry (so one step sooner).
    """
    log = CommandLog(WATCHDOG)
    for _, heard, linear, angular in commands:
        log.add(heard, linear, angular)
    reach = int(round(WATCHDOG / STEP)) + (1 if simulator == 'builtin' else 0)
    for index in range(1, steps + 1):
        given = [command for command in commands if command[0] < index]
        latest = given[-1] if given else None
        if latest is not None and index - latest[0] < reach:
            log.applied(index * STEP, latest[2], latest[3])
        else:
            log.applied(index * STEP, 0.0, 0.0)
    return log
