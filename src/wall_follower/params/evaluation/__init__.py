"""The evaluation nodes' parameter tables: grade_case, line_case, course_report, find_trials."""
