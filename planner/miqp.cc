// In progress (issue 2).
