; 4 blocks (as IPC 2000 BLOCKS probBLOCKS-4-0): a tower d-c-b-a to be built from blocks on the table.
(define (problem blocks-4)
  (:domain blocksworld)
  (:objects a b c d - block)
  (:init (clear a) (clear b) (clear c) (clear d) (ontable a) (ontable b) (ontable c) (ontable d) (handempty))
  (:goal (and (on d c) (on c b) (on b a))))
