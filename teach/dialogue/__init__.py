"""The teaching dialogue's language side: phrases, situation questions, model-repair
questions, oracle teachers and dialogue scripts."""
