"""The grader: a solution's launch file run case by case on generated worlds, graded."""
