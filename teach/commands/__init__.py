"""One module per ``teach`` subcommand: NAME, HELP, add_arguments(parser), run(args) -> exit status.

Modules here import only light modules at top level; heavy libraries are imported in ``run``.
"""
