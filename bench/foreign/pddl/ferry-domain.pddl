; Ferry: the classic STRIPS ferry domain of the IPC-era benchmark collections (as distributed with
; the FF and TLPlan planners and used in IPC 2023's learning track): sail, board, debark; typed here.
(define (domain ferry)
  (:requirements :strips :typing)
  (:types car place)
  (:predicates (not-eq ?x - place ?y - place) (at-ferry ?l - place) (at ?c - car ?l - place)
               (empty-ferry) (on ?c - car))
  (:action sail
    :parameters (?from - place ?to - place)
    :precondition (and (not-eq ?from ?to) (at-ferry ?from))
    :effect (and (at-ferry ?to) (not (at-ferry ?from))))
  (:action board
    :parameters (?car - car ?loc - place)
    :precondition (and (at ?car ?loc) (at-ferry ?loc) (empty-ferry))
    :effect (and (on ?car) (not (at ?car ?loc)) (not (empty-ferry))))
  (:action debark
    :parameters (?car - car ?loc - place)
    :precondition (and (on ?car) (at-ferry ?loc))
    :effect (and (at ?car ?loc) (empty-ferry) (not (on ?car)))))
