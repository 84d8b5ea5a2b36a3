"""The phrases a new teacher used (issue 21), in English and German, do in a session what
they mean: undo words undo, done words finish, unclear words are not guessed into a step,
'why' takes what the prompt takes, and 'no' with nothing asked says how to undo."""

from __future__ import annotations

import pytest
from conftest import ROOT
from test_session import teach_two_demonstrations

from teach import messages as m
from teach.demos import read_demo_set
from teach.domain import load_domain
from teach.learn.learner import Update
from teach.messages import Lang
from teach.session.describe import describe_update
from teach.session.machine import SessionManager
from teach.session.replies import ReplyKind
from teach.session.settings import Settings
from teach.world.symbolic import SymbolicWorld

WHOLE = {"en": "look for the ball, go to the ball, grab it, go to the bin, drop the ball",
         "de": "Ball suchen, Geh mal hin zum Ball, nimm ihn, zum Eimer, leg ihn rein"}


def session(ball, tmp_path, lang: str, questions: int = 0) -> SessionManager:
    settings = Settings("words", lang=lang, questions=questions, base=tmp_path, world="symbolic", record=False)
    return SessionManager(settings, ball, SymbolicWorld(ball))


def said(manager: SessionManager, line: str) -> str:
    return "\n".join(r.text for r in manager.handle(line))


def open_actions(manager: SessionManager) -> list[int]:
    return [step.action for step in manager.open.steps] if manager.open is not None else []


@pytest.mark.parametrize(("lang", "find", "approach", "wrong", "take_back"), [
    ("en", "look for the ball", "go to teh ball", "no, that was wrong", "oops, take that back"),
    ("en", "search for the ball", "approach the ball", "that was wrong", "take that back"),
    ("de", "Ball suchen", "Geh mal hin zum Ball", "nein, das war falsch", "falsch"),
    ("de", "such den Ball", "zum Ball gehen", "das war falsch", "nimm das zurück"),
])
def test_undo_words_take_back_the_last_step(ball, tmp_path, lang, find, approach, wrong, take_back):
    manager = session(ball, tmp_path, lang)
    said(manager, find)
    said(manager, approach)
    assert open_actions(manager) == [1, 2]
    said(manager, wrong)
    assert open_actions(manager) == [1]
    said(manager, take_back)
    assert open_actions(manager) == []


@pytest.mark.parametrize(("lang", "done"), [("en", "that's it"), ("en", "finished"), ("en", "I'm finished"),
                                            ("en", "all done"), ("en", "that's all"), ("en", "task complete"),
                                            ("de", "das war's"), ("de", "erledigt"), ("de", "ich bin fertig"),
                                            ("de", "das war alles"), ("de", "das wars dann")])
def test_done_words_finish_the_demonstration(ball, tmp_path, lang, done):
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang])
    assert open_actions(manager) == [1, 2, 3, 4, 5]
    reply = said(manager, done)
    assert "Did you mean" not in reply and "Meintest" not in reply
    _, [demo] = read_demo_set(tmp_path / "demos" / "words")
    assert [step.action for step in demo.steps] == [1, 2, 3, 4, 5, 0]


@pytest.mark.parametrize(("lang", "done"), [("en", "finished"), ("en", "that's it"), ("de", "das war's")])
def test_a_done_word_before_the_task_is_done_is_refused_never_read_as_an_action(ball, tmp_path, lang, done):
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang].split(",")[0])
    replies = manager.handle(done)
    assert [r.kind for r in replies] == [ReplyKind.ERROR] and manager.suggestion is None
    assert open_actions(manager) == [1]  # "finished" once offered "find the ball": Enter would record it


@pytest.mark.parametrize(("lang", "line"), [("en", "go for it"), ("de", "Nimm gehen!")])
def test_unclear_words_are_not_guessed_into_a_step(ball, tmp_path, lang, line):
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang].split(",")[0])
    reply = said(manager, line)
    assert manager.suggestion is None and "Did you mean" not in reply and "Meintest" not in reply
    assert said(manager, "") == "" and open_actions(manager) == [1]  # Enter records nothing


@pytest.mark.parametrize("line", ["go get it", "go and grab it", "go get the ball", "Go and get the ball!"])
def test_an_errand_is_the_step_it_sends_the_robot_on(ball, tmp_path, line):
    """ "go get it" was once guessed as "go to the bin", then unknown: it is "get it" (grasp the
    ball); with the ball out of reach that is refused with the way there, nothing recorded."""
    manager = session(ball, tmp_path, "en")
    said(manager, "look for the ball")
    reply = said(manager, line)
    assert "To get there: go to the ball." in reply and open_actions(manager) == [1]
    said(manager, "go to the ball")
    said(manager, line)
    assert manager.suggestion is None and open_actions(manager) == [1, 2, 3]


@pytest.mark.parametrize("line", ["go there", "go to it"])
def test_go_before_a_place_is_no_errand(ball, tmp_path, line):
    manager = session(ball, tmp_path, "en")
    said(manager, "look for the ball")
    said(manager, line)
    assert open_actions(manager) == [1, 2]


@pytest.mark.parametrize(("lang", "line"), [("en", "go back"), ("en", "step back"), ("en", "back"),
                                            ("de", "geh zurück"), ("de", "einen Schritt zurück")])
def test_going_back_in_a_world_without_such_a_step_is_undo(ball, tmp_path, lang, line):
    """ "go back" in the ball world was "I don't know “go back”"; where the domain has no step of
    those words, a careless teacher means the last step taken back."""
    manager = session(ball, tmp_path, lang)
    said(manager, "look for the ball, go to the ball" if lang == "en" else "Ball finden, zum Ball gehen")
    assert said(manager, line).startswith(("Undone: step 2", "Rückgängig: Schritt 2"))
    assert open_actions(manager) == [1]


def test_going_back_is_the_step_where_the_domain_has_it(tmp_path):
    """Snacks' "go back" (to the office) stays a step, not 'undo'."""
    snacks = load_domain(ROOT / "demos" / "snacks" / "domain.toml")
    manager = session(snacks, tmp_path, "en")
    said(manager, "wait for a request, take the tray, find someone")
    said(manager, "go back")
    assert snacks.action(open_actions(manager)[-1]).name == "ReturnToOffice"


@pytest.mark.parametrize(("lang", "line"), [("en", "start over"), ("en", "Start again!"), ("en", "from the beginning"),
                                            ("de", "nochmal von vorn"), ("de", "von vorne")])
def test_starting_over_is_a_new_start(ball, tmp_path, lang, line):
    """ "start over" was "unknown condition 'over'" (read as 'start' with conditions)."""
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang])
    said(manager, "fertig" if lang == "de" else "done")
    reply = said(manager, line)
    assert "condition" not in reply and "Bedingung" not in reply
    assert manager.world.state() == (False,) * len(ball.conditions)


@pytest.mark.parametrize(("lang", "line"), [("en", "now you try"), ("en", "Your turn!"), ("en", "try again"),
                                            ("en", "keep going"), ("de", "jetzt du"), ("de", "mach weiter"),
                                            ("en", "go"), ("en", "Go ahead!"), ("en", "off you go"),
                                            ("de", "leg los"), ("de", "fang an"), ("en", "try"),
                                            ("en", "can you do it now?"), ("en", "show me what you can do")])
def test_handing_over_lets_the_robot_run(ball, tmp_path, lang, line):
    """ "now you try" and "go" after a demonstration were "I don't know": they are 'run' ("go to the
    bin please" stays a step: ``test_phrases``)."""
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang])
    said(manager, "fertig" if lang == "de" else "done")
    said(manager, "neu" if lang == "de" else "reset")
    said(manager, line)
    assert manager.world.state()[ball.condition_names.index("BallPlaced")]


@pytest.mark.parametrize(("lang", "line"), [("en", "any questions?"), ("en", "Do you have any questions?"),
                                            ("de", "hast du Fragen?"), ("de", "Noch Fragen?")])
def test_asking_for_questions_lets_the_robot_ask(ball, tmp_path, lang, line):
    manager = session(ball, tmp_path, lang, questions=5)
    said(manager, WHOLE[lang])
    said(manager, "fertig" if lang == "de" else "done")
    if manager.pending is not None:
        said(manager, "skip" if lang == "en" else "weiter")
    used = manager.budget.used
    said(manager, line)
    assert manager.pending is not None and manager.budget.used == used + 1


@pytest.mark.parametrize("line", ["hingehen", "Hingehen!", "geh hin", "geh da hin", "fahr dort hin"])
def test_hingehen_after_the_ball_was_named_goes_to_it(ball, tmp_path, line):
    """ "hingehen" was once guessed as "Ball nehmen", then unclear; it is "hin gehen", read as "geh hin"
    is: to what was named last."""
    manager = session(ball, tmp_path, "de")
    said(manager, WHOLE["de"].split(",")[0])
    said(manager, line)
    assert manager.suggestion is None and open_actions(manager) == [1, 2]


@pytest.mark.parametrize(("lang", "line"), [("en", "drop the ball"), ("de", "Ball fallen lassen"),
                                            ("de", "rein damit"), ("de", "leg ihn rein")])
def test_putting_words_put_the_ball_in_and_are_no_event(ball, tmp_path, lang, line):
    manager = session(ball, tmp_path, lang)
    said(manager, ", ".join(WHOLE[lang].split(", ")[:4]))
    said(manager, line)
    assert open_actions(manager) == [1, 2, 3, 4, 5]


@pytest.mark.parametrize(("lang", "question"), [("en", "why grab"), ("en", "why grab it"), ("en", "why grasp teh ball"),
                                                ("en", "why drop the ball"), ("de", "warum greifen"),
                                                ("de", "warum nimm ihn"), ("de", "warum Ball fallen lassen")])
def test_why_takes_what_the_prompt_takes(ball, tmp_path, lang, question):
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang])
    said(manager, "done")
    replies = manager.handle(question)
    assert [r.kind for r in replies] == [ReplyKind.INFO] and replies[0].text.startswith("- ")


@pytest.mark.parametrize(("lang", "no", "hint"), [("en", "no", "'undo'"), ("en", "nope", "'undo'"),
                                                  ("de", "nein", "'zurück'")])
def test_no_with_nothing_asked_says_how_to_undo(ball, tmp_path, lang, no, hint):
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang].split(",")[0])
    assert hint in said(manager, no) and open_actions(manager) == [1]


@pytest.mark.parametrize(("lang", "yes", "reply"), [("en", "yes", "No question is open."),
                                                     ("de", "ja", "Es ist keine Frage offen."),
                                                     ("en", "maybe", "No question is open."),
                                                     ("en", "hmm, I think so", "No question is open."),
                                                     ("de", "vielleicht", "Es ist keine Frage offen.")])
def test_yes_with_nothing_asked_says_so(ball, tmp_path, lang, yes, reply):
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang].split(",")[0])
    assert said(manager, yes) == reply and open_actions(manager) == [1]


@pytest.mark.parametrize("line", ["thats it", "that's it", "im finished"])
def test_done_as_people_type_it(ball, tmp_path, line):
    manager = session(ball, tmp_path, "en")
    said(manager, WHOLE["en"])
    said(manager, line)
    assert open_actions(manager) == [] and len(manager.demos) == 1


def test_no_still_answers_a_did_you_mean(ball, tmp_path):
    manager = session(ball, tmp_path, "en")
    said(manager, "finding")
    assert manager.suggestion is not None
    said(manager, "no")
    assert manager.suggestion is None and open_actions(manager) == []


def test_wrong_to_an_open_question_is_no_answer_and_no_undo(ball, tmp_path):
    manager = session(ball, tmp_path, "en", questions=3)
    teach_two_demonstrations(manager)
    assert manager.pending is not None  # two demonstrations: a question is open
    reply = said(manager, "wrong")
    assert manager.pending is not None and len(manager.demos) == 2 and "undo" not in reply.lower()


def test_one_step_learned_is_said_as_one(ball):
    """"I learned the steps unstack c b" for one step: one step is "the step", several "the steps"."""
    changed = Update("question 1", tree_changed=True)
    assert describe_update(changed, ["GraspBall"], ball, Lang.EN) == "I learned the step grasp the ball."
    assert describe_update(changed, ["FindBall", "GraspBall"], ball, Lang.EN).startswith("I learned the steps ")
    assert describe_update(changed, ["GraspBall"], ball, Lang.DE).startswith("Ich habe den Schritt ")


@pytest.mark.parametrize(("start", "line", "steps"), [("start BallFound", "los zum Ball", [2]),
                                                    ("start", "los, such den Ball", [1])])
def test_a_number_command_followed_by_steps_is_those_steps(ball, tmp_path, start, line, steps):
    """'los' (run) and 'zurück' (undo) take a number: "los zum Ball" was "expected a whole number"."""
    manager = session(ball, tmp_path, "de")
    said(manager, start)
    assert "error" not in [r.kind.value for r in manager.handle(line)]
    assert open_actions(manager) == steps


def test_back_to_the_office_is_a_step_not_an_undo(tmp_path):
    snacks = load_domain(ROOT / "demos" / "snacks" / "domain.toml")
    settings = Settings("words", lang="de", questions=0, base=tmp_path, world="symbolic", record=False)
    manager = SessionManager(settings, snacks, SymbolicWorld(snacks))

    def shown() -> list[str]:
        return [snacks.action(a).name for a in open_actions(manager)]

    for line in ("auf einen Auftrag warten", "Tablett nehmen", "jemanden suchen", "zurück ins Büro"):
        said(manager, line)
    assert shown() == ["WaitForRequest", "TakeTray", "FindPartner", "ReturnToOffice"]
    said(manager, "zurück 3")  # a number is still an undo
    assert shown() == ["WaitForRequest", "TakeTray"]
    assert "Zahl" in said(manager, "zurück xyz") and len(shown()) == 2  # neither: the undo's error


@pytest.mark.parametrize(("lang", "line"), [("en", "What did you learn?"), ("en", "what have you learned"),
                                            ("de", "Was hast du gelernt?")])
def test_asking_what_it_learned_shows_the_tree(ball, tmp_path, lang, line):
    """"what did you learn?" was "I don't know": it is 'show'."""
    manager = session(ball, tmp_path, lang)
    teach_two_demonstrations(manager)
    assert [r.kind for r in manager.handle(line)] == [ReplyKind.TREE]


def test_a_line_that_names_nothing_is_told_what_can_happen_too(ball, tmp_path):
    """"jemand nimmt den Ball weg" was answered with the robot's actions only: a teacher reporting
    what happened did not learn how the world's events are said. Now they follow ("etwas ändern" in
    the symbolic world; in MuJoCo "den Ball wegnehmen", …)."""
    manager = session(ball, tmp_path, "de")
    told = said(manager, "jemand nimmt den Ball weg")
    assert "Ich kann: Ball finden" in told
    assert "Was dabei passieren kann (sag es, wenn es passiert): etwas ändern" in told


@pytest.mark.parametrize(("lang", "line"), [("en", "well done"), ("en", "Great, well done!"), ("en", "thank you robot"),
                                            ("de", "gut gemacht"), ("de", "Danke!")])
def test_praise_after_a_run_is_thanked_back(ball, tmp_path, lang, line):
    """ "well done" after the robot finished was "You have not shown me any steps yet" (read as 'done')."""
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang])
    said(manager, "fertig" if lang == "de" else "done")
    said(manager, "neu" if lang == "de" else "reset")
    said(manager, "los" if lang == "de" else "run")
    replies = manager.handle(line)
    assert [(r.kind, r.text) for r in replies] == [(ReplyKind.INFO, "Danke!" if lang == "de" else "Thank you!")]


@pytest.mark.parametrize("line", ["well done", "thanks"])
def test_praise_during_a_demonstration_says_what_comes_next_and_ends_nothing(ball, tmp_path, line):
    manager = session(ball, tmp_path, "en")
    said(manager, WHOLE["en"].split(",")[0])
    assert "Tell me the next step" in said(manager, line) and open_actions(manager) == [1] and not manager.demos
    said(manager, ", ".join(WHOLE["en"].split(", ")[1:]))
    assert "say 'done' if this is how it should end" in said(manager, line) and not manager.demos


@pytest.mark.parametrize(("lang", "line", "actions"), [("en", "good, now go to the ball", [1, 2]),
                                                        ("en", "thanks, that was wrong", []),
                                                        ("de", "super, jetzt zum Ball", [1, 2])])
def test_praise_before_a_step_or_command_is_set_aside(ball, tmp_path, lang, line, actions):
    """ "good, now go to the ball" was "I don't know 'good'"."""
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang].split(",")[0])
    said(manager, line)
    assert open_actions(manager) == actions


@pytest.mark.parametrize(("lang", "line"), [("en", "where is the ball?"), ("en", "what do you see?"),
                                            ("en", "Where are you"), ("de", "wo ist der Ball?"),
                                            ("de", "was siehst du"), ("en", "what are you doing?"),
                                            ("de", "was machst du?")])
def test_asking_where_things_are_shows_the_situation(ball, tmp_path, lang, line):
    """ "where is the ball?" and "what do you see" were "I don't know"."""
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang].split(",")[0])
    replies = manager.handle(line)
    assert [r.kind for r in replies] == [ReplyKind.STATE] and open_actions(manager) == [1]


@pytest.mark.parametrize(("lang", "line"), [("en", "bye"), ("en", "Goodbye!"), ("de", "tschüss"), ("de", "ciao")])
def test_saying_goodbye_saves_and_leaves(ball, tmp_path, lang, line):
    """ "bye" was "I don't know 'bye'"; with steps open it warns first, as 'quit' does."""
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang].split(",")[0])
    said(manager, line)
    assert not manager.finished
    said(manager, line)
    assert manager.finished


@pytest.mark.parametrize(("lang", "line"), [("en", "hello"), ("en", "Hi robot!"), ("de", "hallo"),
                                            ("de", "Guten Morgen")])
def test_a_greeting_is_greeted_back(ball, tmp_path, lang, line):
    """ "hallo" was "Did you mean 'halt'?"."""
    manager = session(ball, tmp_path, lang)
    replies = manager.handle(line)
    assert [r.kind for r in replies] == [ReplyKind.SAY] and replies[0].text.startswith(("Hello!", "Hallo!"))


@pytest.mark.parametrize(("lang", "line"), [("en", "hey, find the ball"), ("de", "hallo, such den Ball")])
def test_a_greeting_before_a_step_is_set_aside(ball, tmp_path, lang, line):
    manager = session(ball, tmp_path, lang)
    said(manager, line)
    assert open_actions(manager) == [1]


@pytest.mark.parametrize(("lang", "line"), [("de", "nimm ihn dir"), ("en", "grab it yourself")])
def test_a_step_for_yourself_is_the_step(ball, tmp_path, lang, line):
    """ "nimm ihn dir" ("take it for yourself") was "I don't know"."""
    manager = session(ball, tmp_path, lang)
    said(manager, ", ".join(WHOLE[lang].split(", ")[:2]))
    said(manager, line)
    assert open_actions(manager) == [1, 2, 3]


@pytest.mark.parametrize(("lang", "line", "reply"), [
    ("en", "I can see the ball now", "Yes, I know: I can see the ball."),
    ("en", "the ball is in the bin", "That is not what I see: the ball is not in the bin."),
    ("de", "der Ball ist jetzt im Eimer", "Das sehe ich anders: der Ball ist nicht im Eimer."),
    ("de", "ich sehe den Ball", "Ja, ich weiß: ich sehe den Ball.")])
def test_telling_the_robot_how_things_are_is_answered_and_changes_nothing(ball, tmp_path, lang, line, reply):
    """ "the tray is empty now" was "I don't know": the robot agrees, or says what it sees instead and
    what could have made it so; the world, not a line, decides."""
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang].split(",")[0])
    before = manager.world.state()
    assert said(manager, line).startswith(reply)
    assert manager.world.state() == before and open_actions(manager) == [1]


GREETING_DOMAIN = '''name = "greeter"
goal = ["Greeted"]

[[condition]]
name = "Greeted"
en = "I have greeted the visitor"
de = "ich habe den Besuch begrüßt"

[[action]]
id = 1
name = "Greet"
en = ["say hello", "hello", "thank you"]
de = ["hallo sagen", "hallo"]
pre = ["!Greeted"]
ram = ["Greeted"]
'''


@pytest.mark.parametrize("line", ["hello", "thank you"])
def test_a_domain_phrase_stays_a_step_though_it_sounds_like_courtesy(tmp_path, line):
    """A domain whose robot greets: its phrase "hello" is the step, not a greeting to the robot."""
    (tmp_path / "domain.toml").write_text(GREETING_DOMAIN, encoding="utf-8")
    greeter = load_domain(tmp_path / "domain.toml")
    manager = session(greeter, tmp_path, "en")
    said(manager, line)
    assert open_actions(manager) == [1]


@pytest.mark.parametrize(("lang", "line", "reply"), [("en", "sorry", "All right."), ("en", "never mind", "All right."),
                                                     ("en", "ok", "All right."), ("de", "schon gut", "In Ordnung."),
                                                     ("de", "alles klar", "In Ordnung.")])
def test_a_line_that_asks_for_nothing_is_let_be(ball, tmp_path, lang, line, reply):
    """ "sorry" was "I don't know 'sorry'" and a list of what the robot can do, "ok" "No question is
    open"; during a demonstration the reply says what comes next."""
    manager = session(ball, tmp_path, lang)
    assert said(manager, line) == reply
    said(manager, WHOLE[lang].split(",")[0])
    assert said(manager, line) == f"{reply} {m.GO_ON(Lang.parse(lang))}" and open_actions(manager) == [1]


@pytest.mark.parametrize(("lang", "line"), [("en", "hello"), ("de", "Guten Morgen")])
def test_a_greeting_during_a_demonstration_says_what_comes_next(ball, tmp_path, lang, line):
    """It repeated the whole opening line ("Show me how to do the task … I can: …")."""
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang].split(",")[0])
    replies = manager.handle(line)
    hello = m.HELLO_AGAIN(Lang.parse(lang))
    assert [(r.kind, r.text) for r in replies] == [(ReplyKind.SAY, f"{hello} {m.GO_ON(Lang.parse(lang))}")]
    assert open_actions(manager) == [1]


@pytest.mark.parametrize("line", ["👍", "great :)", "👏👏", "thumbs up", "cool"])
def test_praise_in_marks_is_thanked_back(ball, tmp_path, line):
    """ "👍" was "I don't know '👍'" (and "thumbs up", "cool")."""
    manager = session(ball, tmp_path, "en")
    said(manager, WHOLE["en"].split(",")[0])
    assert said(manager, line) == f"Thank you! {m.GO_ON(Lang.EN)}" and open_actions(manager) == [1]


def test_a_thumb_to_may_i_is_asked_back_as_a_yes(ball, tmp_path):
    """A care robot does not act on a "👍": it asks whether that is a yes, and the question stays open."""
    manager = session(ball, tmp_path, "en", questions=3)
    teach_two_demonstrations(manager)
    asked = manager.pending
    assert asked is not None and asked.kind.startswith("must-")
    assert said(manager, "👍") == m.IS_THAT_A_YES(Lang.EN) and manager.pending is asked


@pytest.mark.parametrize(("lang", "line"), [("en", "hmm"), ("en", "wait"), ("en", "hold on, robot"),
                                            ("de", "einen Moment"), ("de", "warte mal")])
def test_asking_the_robot_to_wait_is_waited_for(ball, tmp_path, lang, line):
    """ "wait" and "hmm" were "I don't know" and a list of actions: nothing is done."""
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang].split(",")[0])
    assert said(manager, line) == f"{m.TAKE_YOUR_TIME(Lang.parse(lang))} {m.GO_ON(Lang.parse(lang))}"
    assert open_actions(manager) == [1]


@pytest.mark.parametrize("line", ["hmm", "wait a moment"])
def test_waiting_leaves_a_question_open(ball, tmp_path, line):
    manager = session(ball, tmp_path, "en", questions=3)
    teach_two_demonstrations(manager)
    asked = manager.pending
    assert asked is not None
    assert said(manager, line) == m.TAKE_YOUR_TIME_ASKED(Lang.EN) and manager.pending is asked


@pytest.mark.parametrize(("lang", "line"), [("en", "wait, no"), ("en", "no wait"), ("de", "nein, warte")])
def test_a_no_with_a_wait_is_a_no(ball, tmp_path, lang, line):
    """ "wait, no" was "I don't know": with nothing asked it says how to take a step back."""
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang].split(",")[0])
    assert said(manager, line) == m.NO_TO_WHAT(Lang.parse(lang)) and open_actions(manager) == [1]


@pytest.mark.parametrize(("lang", "line"), [("en", "undo undo"), ("de", "zurück zurück")])
def test_a_command_said_twice_is_done_once(ball, tmp_path, lang, line):
    """ "undo undo" was "expected a whole number, not 'undo'"."""
    manager = session(ball, tmp_path, lang)
    said(manager, ", ".join(WHOLE[lang].split(", ")[:2]))
    said(manager, line)
    assert open_actions(manager) == [1]


@pytest.mark.parametrize("line", ["huh?", "what do you mean?", "say that again", "wie bitte?"])
def test_a_puzzled_answer_gets_the_question_again(ball, tmp_path, line):
    """ "huh?" was "I don't know 'huh?'" and a list of answers, without the question."""
    manager = session(ball, tmp_path, "en", questions=3)
    teach_two_demonstrations(manager)
    asked = manager.pending
    assert asked is not None
    replies = manager.handle(line)
    assert replies[0].text == m.QUESTION_AGAIN(Lang.EN) and replies[1].kind is ReplyKind.QUESTION
    assert manager.pending is asked and manager.budget.used == 1


@pytest.mark.parametrize(("line", "ruled_out"), [("that makes no sense", False), ("how can that be?", False),
                                                 ("that's not possible", True), ("das geht nicht", True)])
def test_doubting_a_situation_is_asked_back_and_not_possible_rules_it_out(ball, tmp_path, line, ruled_out):
    """ "that makes no sense" is asked back (the robot does not guess that a situation cannot
    happen); "that's not possible" says it cannot, as "that cannot happen" does."""
    manager = session(ball, tmp_path, "en", questions=3)
    teach_two_demonstrations(manager)
    asked = manager.pending
    assert asked is not None
    replies = manager.handle(line)
    if ruled_out:
        assert replies[0].text == m.CANNOT_HAPPEN(Lang.EN) and manager.pending is not asked
    else:
        assert [r.text for r in replies] == [m.CANNOT_HAPPEN_THEN(Lang.EN)] and manager.pending is asked


@pytest.mark.parametrize(("line", "yes"), [("go ahead", True), ("sure, go ahead", True), ("yes you may", True),
                                           ("no you may not", False), ("no, don't", False)])
def test_everyday_yes_and_no_answer_may_i(ball, tmp_path, line, yes):
    """ "go ahead" to "may I …?" was "Please answer my question first" (it is also 'run'), "sure, go
    ahead" and "yes you may" "I don't know"; "no you may not" was "I take that as a no (I don't know
    'you may not')"."""
    manager = session(ball, tmp_path, "en", questions=3)
    teach_two_demonstrations(manager)
    asked = manager.pending
    assert asked is not None and asked.kind.startswith("must-")
    replies = manager.handle(line)
    if yes:
        assert replies[0].text.startswith("Thank you.") and manager.pending is not asked
    else:
        assert [r.text for r in replies] == [m.WHAT_INSTEAD(Lang.EN)] and manager.pending is asked


@pytest.mark.parametrize(("lang", "step", "yes"), [("en", "grab it", "yes"), ("en", "grab it", ""),
                                                   ("de", "nimm ihn", "ja")])
def test_the_way_to_a_refused_step_is_done_on_a_yes(ball, tmp_path, lang, step, yes):
    """ "grab it" before the ball was within reach was refused with "To get there: go to the ball.",
    and the teacher had to type both steps; now a yes (or Enter) does the way and then the step."""
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang].split(",")[0])
    offered = said(manager, step)
    assert ("Say 'yes' and I do that" in offered or "Sag 'ja', dann tue ich das" in offered)
    assert open_actions(manager) == [1]
    said(manager, yes)
    assert open_actions(manager) == [1, 2, 3]


def test_a_no_to_the_way_does_nothing(ball, tmp_path):
    manager = session(ball, tmp_path, "en")
    said(manager, "find the ball")
    said(manager, "grab it")
    assert said(manager, "no") == "All right." and open_actions(manager) == [1]
    assert said(manager, "yes") == "No question is open."  # the offer was for the line after it only


@pytest.mark.parametrize("line", ["that's it", "thats it", "das war's"])
def test_that_s_it_after_an_offered_way_is_the_task_finished_not_a_yes(ball, tmp_path, line):
    """ "thats it" said to "To get there: go to the ball, grasp the ball. Say 'yes' and I do that,
    then put the ball in the bin." was read as the yes: the robot went off doing three steps."""
    manager = session(ball, tmp_path, "en")
    said(manager, "find the ball")
    assert "Say 'yes' and I do that" in said(manager, "drop it in")
    reply = said(manager, line)
    assert open_actions(manager) == [1] and "The task is not finished yet" in reply


def test_a_decimal_point_does_not_split_a_line(ball, tmp_path):
    """ "giude forward 0.2" was said back as "I don't know “giude forward 0”": the line was cut at
    the decimal point as at a full stop."""
    manager = session(ball, tmp_path, "en")
    assert "“giude forward 0.2”" in said(manager, "giude forward 0.2")
    said(manager, "find the ball. go to the ball")
    assert open_actions(manager) == [1, 2]  # a full stop still ends a step


@pytest.mark.parametrize(("lang", "again"), [("en", "again"), ("en", "once more"), ("en", "can you do it again?"),
                                             ("de", "nochmal"), ("de", "kannst du das nochmal machen?")])
def test_again_right_after_a_step_is_that_step(tmp_path, lang, again):
    """ "again" alone was "I don't know “again”" (with "grab it again" understood)."""
    snacks = load_domain(ROOT / "demos" / "snacks" / "domain.toml")
    settings = Settings("words", lang=lang, questions=0, base=tmp_path, world="symbolic", record=False)
    manager = SessionManager(settings, snacks, SymbolicWorld(snacks))
    find = snacks.action("FindPartner").label(Lang(lang))
    said(manager, find)
    assert said(manager, again).startswith(f"– {find}:")  # that step (so already: passed over)
    assert said(manager, again).startswith(m.AGAIN_WHAT(Lang(lang), example="")[:8])  # after nothing done: which?
    assert [snacks.action(a).name for a in open_actions(manager)] == ["FindPartner"]


def test_again_after_anything_but_a_step_asks_which(ball, tmp_path):
    manager = session(ball, tmp_path, "en")
    said(manager, "find the ball")
    said(manager, "grab it")  # refused: the ball is out of reach
    assert said(manager, "again").startswith("Do what again?") and open_actions(manager) == [1]


def test_a_hmm_keeps_what_waits_for_a_yes(ball, tmp_path):
    """ "hlep" → "Did you mean “help”?", "hmm" → "Take your time.", "yes" was "No question is open":
    the offer was for the line after it only; a "hmm" now keeps it, as it keeps an offered way."""
    manager = session(ball, tmp_path, "en")
    assert said(manager, "hlep").endswith("Did you mean “help”?")
    assert said(manager, "hmm") == m.TAKE_YOUR_TIME(Lang.EN)
    assert said(manager, "yes").startswith(m.HELP_INTRO(Lang.EN, examples="")[:10])
    said(manager, "find the ball")
    assert "Say 'yes' and I do that" in said(manager, "grab it")
    said(manager, "hmm, wait")
    said(manager, "yes")
    assert open_actions(manager) == [1, 2, 3]


@pytest.mark.parametrize(("lang", "find", "slip", "meant"), [
    ("en", "find the ball", "go to the bin", "oops, I meant go to the ball"),
    ("en", "find the ball", "go to the bin", "sorry, I meant to say go to the ball"),
    ("de", "Ball finden", "zum Eimer", "nein, ich meinte zum Ball")])
def test_i_meant_takes_the_last_step_back_and_does_what_was_meant(ball, tmp_path, lang, find, slip, meant):
    """ "oops, I meant go to the ball" was "expected a whole number, not 'i meant go ball'" ('oops'
    is an undo)."""
    manager = session(ball, tmp_path, lang)
    said(manager, find)
    said(manager, slip)
    reply = said(manager, meant)
    assert open_actions(manager) == [1, 2] and reply.index("2") < reply.index("✓")  # undone, then done


@pytest.mark.parametrize("undo", ["undo that", "undo the last one", "no wait, undo that", "nimm das zurück"])
def test_undo_that_takes_the_last_step_back(ball, tmp_path, undo):
    """ "undo that" was "expected a whole number, not 'that'"."""
    manager = session(ball, tmp_path, "en")
    said(manager, "find the ball, go to the ball")
    said(manager, undo)
    assert open_actions(manager) == [1]


@pytest.mark.parametrize(("lang", "line"), [("en", "can you find the ball for me?"),
                                            ("en", "find the ball for us please"), ("de", "such den Ball für mich")])
def test_a_step_asked_for_someone_is_that_step(ball, tmp_path, lang, line):
    """ "can you find the ball for me?" was "Did you mean “find the ball”?"."""
    manager = session(ball, tmp_path, lang)
    said(manager, line)
    assert open_actions(manager) == [1]


@pytest.mark.parametrize(("lang", "doubt", "step"), [("en", "are you sure?", "find the ball"),
                                                     ("en", "why did you do that?", "find the ball"),
                                                     ("de", "bist du sicher?", "Ball finden"),
                                                     ("de", "warum hast du das gemacht?", "Ball finden")])
def test_a_doubt_right_after_a_step_is_told_why_it_was_done(ball, tmp_path, lang, doubt, step):
    """ "are you sure?" was "I don't know “are you sure?”", "why did you do that?" "No tree yet."."""
    manager = session(ball, tmp_path, lang)
    assert said(manager, doubt) == m.NO_STEP_JUST_NOW(Lang(lang))  # nothing done yet: no tree to name either
    said(manager, step)
    label = ball.action("FindBall").label(Lang(lang))
    assert said(manager, doubt) == m.DID_AS_ASKED(Lang(lang), action=label)
    assert said(manager, "why") == m.DID_AS_ASKED(Lang(lang), action=label)  # a doubt keeps what it is about
    assert open_actions(manager) == [1]


def test_a_doubt_after_a_run_gives_the_trees_reasons(ball, tmp_path):
    manager = session(ball, tmp_path, "en")
    teach_two_demonstrations(manager)
    said(manager, "reset")
    assert "I did: find the ball" in said(manager, "run 1")
    reply = said(manager, "why did you do that?")
    assert reply.startswith(m.DID_AS_LEARNED(Lang.EN, action="find the ball")) and "\n- " in reply
    assert said(manager, "are you sure?") == reply


@pytest.mark.parametrize(("lang", "undo"), [("en", "undo to step two"), ("en", "undo two"),
                                            ("de", "zurück bis Schritt zwei")])
def test_a_step_number_said_in_words_is_that_number(ball, tmp_path, lang, undo):
    """ "undo to step two" was "expected a whole number, not 'step two'" (steps 2 to the end go)."""
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang])
    said(manager, undo)
    assert open_actions(manager) == [1]
    said(manager, WHOLE[lang][WHOLE[lang].index(",") + 1:])
    said(manager, "done")
    said(manager, "reset")
    said(manager, "run two" if lang == "en" else "los zwei")
    assert manager.world.state() == ball.state(["BallFound", "BallClose"])  # two steps of the learned tree


def test_again_right_after_a_run_runs_again(ball, tmp_path):
    """ "again" after `run 1` asked "Do what again?"."""
    manager = session(ball, tmp_path, "en")
    teach_two_demonstrations(manager)
    said(manager, "reset")
    said(manager, "run 1")
    assert "I did: go to the ball" in said(manager, "again")
    assert manager.world.state() == ball.state(["BallFound", "BallClose"])


@pytest.mark.parametrize(("lang", "asked"), [("en", "is it done?"), ("en", "are we done?"), ("de", "ist es fertig?"),
                                             ("de", "bist du fertig?")])
def test_asking_whether_it_is_done_is_answered_from_the_goal(ball, tmp_path, lang, asked):
    """ "is it done?" was "I don't know", "are we done?" ended the demonstration (as "we are done")."""
    manager = session(ball, tmp_path, lang)
    said(manager, "find the ball" if lang == "en" else "Ball finden")
    unmet = ball.condition("BallPlaced").label(Lang(lang), False)
    assert said(manager, asked) == m.NOT_DONE_YET(Lang(lang), unmet=unmet) and open_actions(manager) == [1]
    said(manager, WHOLE[lang][WHOLE[lang].index(",") + 1:])
    assert said(manager, asked) == m.WHAT_NOW_FINISHED(Lang(lang)) and len(open_actions(manager)) == 5


@pytest.mark.parametrize(("lang", "line"), [("en", "who are you?"), ("de", "wer bist du?")])
def test_who_are_you_is_greeted(ball, tmp_path, lang, line):
    """ "who are you" was "Did you mean “why are you”?"."""
    manager = session(ball, tmp_path, lang)
    assert said(manager, line).startswith(m.HELLO_AGAIN(Lang(lang)))


@pytest.mark.parametrize(("lang", "line"), [("en", "let's start over"), ("de", "lass uns von vorn anfangen")])
def test_lets_start_over_is_a_new_start(ball, tmp_path, lang, line):
    """ "let's start over" was "I don't know", "lass uns von vorn anfangen" "Meintest du „lass den Ball fallen“?"."""
    manager = session(ball, tmp_path, lang)
    said(manager, WHOLE[lang])
    said(manager, "fertig" if lang == "de" else "done")
    said(manager, line)
    assert manager.world.state() == (False,) * len(ball.conditions)


def test_what_can_you_do_before_anything_was_learned_says_so_in_words(ball, tmp_path):
    """ "was kannst du?" is 'show' ("was kannst du jetzt"), and with nothing learned it said "Noch kein Baum."."""
    manager = session(ball, tmp_path, "de")
    assert said(manager, "was kannst du?") == m.NO_TREE(Lang.DE) and "Baum" not in m.NO_TREE(Lang.DE)


@pytest.mark.parametrize("lang", ["en", "de"])
def test_a_step_whose_effect_holds_already_is_passed_over_and_the_line_goes_on(ball, tmp_path, lang):
    """A second "find the ball" was "I could not find the ball: first this must be true: I cannot
    see the ball", and the rest of its line was dropped."""
    manager = session(ball, tmp_path, lang)
    find, approach = (ball.action(name).label(Lang(lang)) for name in ("FindBall", "ApproachBall"))
    said(manager, find)
    seen = ball.condition("BallFound").label(Lang(lang), True)
    reply = said(manager, f"{find}, {approach}")
    assert reply.startswith(m.ALREADY_SO(Lang(lang), action=find, so=seen)) and open_actions(manager) == [1, 2]


@pytest.mark.parametrize("lang", ["en", "de"])
def test_help_names_what_one_may_ask_the_robot(ball, tmp_path, lang):
    """The sayings the session answers ("is it done?", "are you sure?") were in no help text."""
    manager = session(ball, tmp_path, lang)
    told = said(manager, "help" if lang == "en" else "hilfe")
    assert told.endswith(m.HELP_ASK(Lang(lang)))
    for asked in ("is it done?", "are you sure?", "what now?") if lang == "en" else ("ist es fertig?",):
        assert asked in told and said(manager, asked) != said(manager, "xyzzy")  # each one is answered


def test_a_step_said_without_its_last_object_is_offered_as_the_steps_possible_here(tmp_path):
    """ "take c off", "put c on", "pick up" in blocksworld were "I don't know" with the first actions
    of the domain: the one step possible here that the words say with an object more is offered
    (a yes does it), several are named."""
    blocks = load_domain(ROOT / "demos" / "blocksworld" / "domain.toml")
    manager = session(blocks, tmp_path, "en")
    manager.handle("start holding a, clear b, clear c, clear d, ontable b, ontable c, ontable d")
    said(manager, "put a on b")
    said(manager, "pick up c")
    assert said(manager, "put c on") == "I don't know “put c on”.\nWhich one: “put c on a” or “put c on d”?"
    said(manager, "put c on a")
    assert said(manager, "take c off") == "I don't know “take c off”. Did you mean “take c off a”?"
    said(manager, "yes")
    assert [blocks.action(a).name for a in open_actions(manager)][-1] == "unstack_c_a"
    assert said(manager, "stack c").endswith("Which one: “stack c a” or “stack c d”?")  # holding c again
    said(manager, "put c down")
    assert "Which one" not in said(manager, "stack c")  # c held by nobody: nothing possible to offer


def test_blocksworld_speaks_german(tmp_path):
    """A German blocksworld session showed "pick_up_a" and "ontable_b" and knew no German step; a
    step already so named every effect ("nicht: a ist frei, …"); "which one" was "„a“ oder „b“ oder „c“"."""
    blocks = load_domain(ROOT / "demos" / "blocksworld" / "domain.toml")
    manager = session(blocks, tmp_path, "de")
    manager.handle("start ich halte a, b ist frei, c ist frei, d ist frei, b liegt auf dem Tisch, c liegt auf dem "
                   "Tisch, d liegt auf dem Tisch")
    assert said(manager, "nimm a von b").startswith("– nimm a von b: schon so – b ist frei und ich halte a (")
    said(manager, "leg es ab")
    said(manager, "heb c auf")
    assert said(manager, "leg c auf").endswith("Welchen davon: „leg c auf a“, „leg c auf b“ oder „leg c auf d“?")
    assert [blocks.action(a).name for a in open_actions(manager)] == ["put_down_a", "pick_up_c"]
