"""The live terminal front-end (prompt_toolkit in, rich out) and the scripted driver that prints
transcripts exactly as the terminal shows them."""
