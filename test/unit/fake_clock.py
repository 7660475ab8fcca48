"""A wall clock for the unit tests of waits: it stands still until sleep() moves it on."""


class FakeClock(object):
    """Call it for the time [s]; pass its sleep as the code's sleep."""

    def __init__(self):
        self.now = 0.0

    def __call__(self):
        return self.now

    def sleep(self, seconds):
        self.now += seconds
