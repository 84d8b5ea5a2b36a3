"""Foreign data for judging learners: planning domains and random STRIPS domains written elsewhere
than the learner, an optimal teacher over their true models, and task success in the true model.

Nothing here reads ``bench/random_domains.py`` or the learner's planner: the teacher plans by
breadth-first search in the true model, so a learner is judged on how the world works, not on
how much it agrees with itself.
"""
