"""Voice: the robot's speech (espeak-ng) and English recognition with the domain's grammar
(pocketsphinx), through the real libraries and the real commands."""

from __future__ import annotations

import ast

import numpy as np
import pytest
from conftest import ROOT

from teach.cli import main
from teach.domain import load_domain
from teach.session.commands import COMMANDS
from teach.voice.audio import Audio, read_wav, with_noise, write_wav
from teach.voice.grammar import domain_grammar, pronoun_forms, spoken_words
from teach.voice.synth import synthesizer

BALL = ROOT / "demos" / "ball" / "domain.toml"


def _round_trip_texts() -> list[str]:
    domain = load_domain(BALL)
    phrases = [" ".join(spoken_words(p)) for action in domain.actions for p in action.en]
    return list(dict.fromkeys(phrases + [command.usage("en").split()[0] for command in COMMANDS]))


def test_every_action_phrase_and_command_word_is_heard_as_itself_clean_and_at_20_db(tmp_path, capsys):
    texts = _round_trip_texts()
    files = []
    for number, text in enumerate(texts):
        clean, noisy = tmp_path / f"{number:03d}.wav", tmp_path / f"{number:03d}-noisy.wav"
        assert main(["speak", text, "-o", str(clean)]) == 0
        write_wav(noisy, with_noise(read_wav(clean), snr_db=20, seed=number))
        files += [clean, noisy]
    capsys.readouterr()
    main(["hear", *map(str, files), "--domain", str(BALL)])  # one process, one decoder: all files in one call
    heard = dict(line.split(": ", 1) for line in capsys.readouterr().out.splitlines())
    clean_right = [t for n, t in enumerate(texts) if heard.get(str(tmp_path / f"{n:03d}.wav")) == t]
    noisy_right = [t for n, t in enumerate(texts) if heard.get(str(tmp_path / f"{n:03d}-noisy.wav")) == t]
    print(f"round trip: {len(clean_right)}/{len(texts)} clean, {len(noisy_right)}/{len(texts)} at 20 dB SNR")
    # at least 95% of them come back word for word, with and without noise
    assert len(clean_right) >= 0.95 * len(texts)
    assert len(noisy_right) >= 0.95 * len(texts)


def test_hear_prints_the_line_and_names_a_file_where_nothing_fits(tmp_path, capsys):
    spoken, silent = tmp_path / "find.wav", tmp_path / "silent.wav"
    assert main(["speak", "find the ball", "-o", str(spoken)]) == 0
    write_wav(silent, Audio(np.zeros(16000, dtype=np.int16), 16000))
    assert main(["hear", str(spoken)]) == 0
    assert capsys.readouterr().out == "find the ball\n"
    assert main(["hear", str(silent)]) == 2
    assert capsys.readouterr().err == f"{silent}: nothing fits\n"


@pytest.mark.parametrize("argv", [["hear", "README.md"], ["hear", "no-such.wav"], ["speak", "  ", "-o", "x.wav"],
                                  ["speak", "x" * 3000, "-o", "x.wav"]])
def test_bad_input_is_one_line_and_status_2(argv, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(ROOT if argv[1] == "README.md" else tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert not (tmp_path / "x.wav").exists()


def test_a_wav_that_is_not_16_bit_is_named(tmp_path, capsys):
    import wave

    with wave.open(str(tmp_path / "8bit.wav"), "wb") as out:
        out.setnchannels(1)
        out.setsampwidth(1)
        out.setframerate(16000)
        out.writeframes(bytes(1600))
    assert main(["hear", str(tmp_path / "8bit.wav")]) == 2
    assert "only 16-bit PCM" in capsys.readouterr().err


def test_german_is_spoken_with_the_german_voice(tmp_path):
    voice = synthesizer()
    assert voice.voice("de") == "de" and voice.voice("en").startswith("en")
    # the same letters, pronounced as German words in German and as English ones in English
    assert "aɪ" in voice.phonemes("Ball greifen", "de") and "ɔː" not in voice.phonemes("Ball greifen", "de")
    assert voice.phonemes("Ball greifen", "de") != voice.phonemes("Ball greifen", "en")
    german, english = tmp_path / "de.wav", tmp_path / "en.wav"
    assert main(["speak", "--lang", "de", "Ball greifen", "-o", str(german)]) == 0
    assert main(["speak", "--lang", "en", "Ball greifen", "-o", str(english)]) == 0
    assert german.read_bytes() != english.read_bytes()


def test_spoken_files_have_durations_and_energy_that_fit_their_text(tmp_path):
    texts = ["Ja.", "Ball greifen.", "Hallo! Zeig mir die Aufgabe Schritt für Schritt."]
    sounds = []
    for number, text in enumerate(texts):
        path = tmp_path / f"{number}.wav"
        assert main(["speak", "--lang", "de", text, "-o", str(path)]) == 0
        sounds.append(read_wav(path))
    seconds = [sound.seconds for sound in sounds]
    # longer text, longer sound; between 3 and 30 characters a second, as people speak
    assert seconds == sorted(seconds)
    for text, sound in zip(texts, sounds, strict=True):
        speech = sound.seconds - 0.5  # the quarter second of silence before and after
        assert 3 <= len(text) / speech <= 30, (text, speech)
        assert 1000 < sound.rms() < 12000  # audible, not clipped
        edge = round(0.2 * sound.rate)
        assert not sound.samples[:edge].any() and not sound.samples[-edge:].any()  # silence around it


def test_the_grammar_holds_pronoun_forms_answers_and_conditions():
    grammar = domain_grammar(load_domain(BALL))
    assert {"grasp it", "take it to the bin", "put it in the bin"} <= set(grammar.actions)
    assert {"yes", "no", "done", "undo", "before", "after"} <= set(grammar.answers)
    assert "the ball is within reach" in grammar.conditions
    assert pronoun_forms(["go to the bin"]) == ["go to it"]
    assert "start <condition>" in grammar.jsgf()


def test_each_voice_library_is_imported_in_one_module():
    def imports(path):
        names = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                names |= {alias.name for alias in node.names}
            elif isinstance(node, ast.ImportFrom) and node.module:
                names.add(node.module)
            elif isinstance(node, ast.Constant) and isinstance(node.value, str) and "." not in node.value:
                names.add(node.value)  # require("pocketsphinx", ...)
        return names

    modules = sorted((ROOT / "teach").rglob("*.py"))
    for library, home in (("espeakng_loader", "synth.py"), ("pocketsphinx", "recognise.py"),
                          ("sounddevice", "device.py")):
        assert [p.name for p in modules if library in imports(p)] == [home]
