"""The planner arguments of the grippers the older tests were written for: two fingers
with friction ``mu``, three frictionless fingers and gravity (straight down), four
frictionless fingers.  A ``mu`` that a planner cannot use is an error and
``fingers=3`` alone means three fingers with friction (tests/test_three_fingers.py)."""


def grip(fingers, mu=0.0):
    """``plan`` keyword arguments for ``fingers`` (3: frictionless with gravity)."""
    if fingers == 2:
        return {"fingers": 2, "mu": mu}
    if fingers == 3:
        return {"fingers": 3, "mu": 0.0, "gravity": (0.0, -1.0)}
    return {"fingers": fingers, "mu": 0.0}
