//! Generational slot bookkeeping, shared by the three arenas.
//!
//! Why not `slotmap` (or the archived `generational-arena`)? Those crates
//! store the generation *inside* each value's slot and give every arena its
//! own key space. meshloom needs three things they do not offer together:
//! twin half-edges that share one generation (so `twin` is arithmetic and costs
//! no storage), attribute columns that sit beside the arena and are indexed by
//! the same slot number, and a free list that costs nothing while no element
//! has been removed (a freshly built mesh has none). Measured in
//! `bench_peers`: this keeps a triangle mesh with f64 positions at about 132
//! heap bytes per vertex, generations included.
//!
//! Until a slot is first reused every live generation is 1, and the arena
//! knows it (`pristine`): making a key for a neighbour then needs no load
//! from `generations`, which cuts a fifth off one-ring circulation on a
//! freshly built mesh (2.5 ms to 2.0 ms on the 250k-vertex grid).
//!
//! Likewise, until a slot is first freed every slot is live at generation
//! 1 (`intact`), so checking a key is a compare with 1 and a bounds test,
//! with no load: reading an attribute by key on a mesh that was loaded and
//! not edited costs what indexing a `Vec` costs.
//!
//! A slot's generation is odd while it is occupied and even while it is
//! vacant, so a live key always has an odd generation and a scan over
//! `generations` alone tells which slots are live.

/// Generations and the free list of one arena.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Slots {
    generations: Vec<u32>,
    free: Vec<u32>,
    live: usize,
    /// True while no slot was ever reused, so every live slot has
    /// generation 1 and making a key needs no load.
    pristine: bool,
    /// True while no slot was ever freed, so every slot is live with
    /// generation 1 and checking a key needs no load either.
    intact: bool,
}

impl Default for Slots {
    fn default() -> Self {
        Slots::with_capacity(0)
    }
}

impl Slots {
    /// Slots with room for `n` elements reserved.
    pub(crate) fn with_capacity(n: usize) -> Self {
        Slots {
            generations: Vec::with_capacity(n),
            free: Vec::new(),
            live: 0,
            pristine: true,
            intact: true,
        }
    }

    /// `n` live slots of generation 1, none vacant (a freshly built arena).
    pub(crate) fn full(n: usize) -> Self {
        Slots {
            generations: vec![1; n],
            free: Vec::new(),
            live: n,
            pristine: true,
            intact: true,
        }
    }

    /// Live elements.
    #[inline]
    pub(crate) fn live(&self) -> usize {
        self.live
    }

    /// Slots ever allocated (live or vacant): the length of every column.
    #[inline]
    pub(crate) fn slot_count(&self) -> usize {
        self.generations.len()
    }

    /// The generation of slot `i`; `None` past the end.
    #[inline]
    pub(crate) fn generation(&self, i: usize) -> Option<u32> {
        self.generations.get(i).copied()
    }

    /// The current generation of a slot known to be live.
    #[inline]
    pub(crate) fn generation_of(&self, i: u32) -> u32 {
        if self.pristine {
            1
        } else {
            self.generations[i as usize]
        }
    }

    /// Whether `(index, generation)` names the live element in its slot.
    #[inline]
    pub(crate) fn is_current(&self, index: u32, generation: u32) -> bool {
        if self.intact {
            generation == 1 && (index as usize) < self.generations.len()
        } else {
            generation & 1 == 1 && self.generations.get(index as usize) == Some(&generation)
        }
    }

    /// Whether no slot was ever freed (every slot live at generation 1).
    #[inline]
    pub(crate) fn intact(&self) -> bool {
        self.intact
    }

    /// Whether slot `i` is occupied.
    #[inline]
    pub(crate) fn is_live(&self, i: usize) -> bool {
        self.generations.get(i).is_some_and(|g| g & 1 == 1)
    }

    /// Slot `i`'s index and generation, if it is live.
    #[inline]
    pub(crate) fn live_at(&self, i: usize) -> Option<(u32, u32)> {
        let i = u32::try_from(i).ok()?;
        self.is_live(i as usize).then(|| (i, self.generation_of(i)))
    }

    /// Take a slot: a vacant one if any, else a new one at the end.
    /// Returns `(index, generation, is_new)`.
    pub(crate) fn alloc(&mut self) -> (u32, u32, bool) {
        self.live += 1;
        if let Some(i) = self.free.pop() {
            self.pristine = false;
            let g = &mut self.generations[i as usize];
            *g = g.wrapping_add(1);
            (i, *g, false)
        } else {
            let i = u32::try_from(self.generations.len()).expect("more than 2^32 slots");
            self.generations.push(1);
            (i, 1, true)
        }
    }

    /// Vacate slot `i`. Keys to it become stale. A slot whose generation
    /// would wrap is retired instead of reused, so no key is ever reissued.
    pub(crate) fn free(&mut self, i: u32) {
        let g = &mut self.generations[i as usize];
        debug_assert!(*g & 1 == 1, "freeing a vacant slot");
        self.intact = false;
        *g = g.wrapping_add(1);
        self.live -= 1;
        if *g < u32::MAX - 1 {
            self.free.push(i);
        }
    }

    /// The live slot indices, in slot order.
    pub(crate) fn live_indices(&self) -> impl Iterator<Item = u32> + '_ {
        self.generations
            .iter()
            .enumerate()
            .filter(|(_, g)| *g & 1 == 1)
            .map(|(i, _)| i as u32)
    }

    /// Heap bytes held.
    pub(crate) fn heap_bytes(&self) -> usize {
        (self.generations.capacity() + self.free.capacity()) * 4
    }

    /// Rebuild from raw generations (deserialization). Vacant slots are the
    /// even ones; the live count follows.
    pub(crate) fn from_generations(generations: Vec<u32>) -> Self {
        let free: Vec<u32> = generations
            .iter()
            .enumerate()
            .filter(|(_, g)| *g & 1 == 0 && **g < u32::MAX - 1)
            .map(|(i, _)| i as u32)
            .rev()
            .collect();
        let live = generations.iter().filter(|g| *g & 1 == 1).count();
        let pristine = generations.iter().all(|&g| g <= 2);
        let intact = generations.iter().all(|&g| g == 1);
        Slots {
            generations,
            free,
            live,
            pristine,
            intact,
        }
    }

    /// The raw generations (serialization).
    pub(crate) fn generations(&self) -> &[u32] {
        &self.generations
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reuse_bumps_generation() {
        let mut s = Slots::default();
        let (a, ga, new) = s.alloc();
        assert!(new && s.is_current(a, ga));
        s.free(a);
        assert!(!s.is_current(a, ga));
        assert!(!s.is_live(a as usize));
        let (b, gb, new) = s.alloc();
        assert_eq!((a, false), (b, new));
        assert_ne!(ga, gb);
        assert!(s.is_current(b, gb) && !s.is_current(a, ga));
        assert_eq!(s.live(), 1);
    }

    #[test]
    fn pristine_until_first_reuse() {
        let mut s = Slots::full(3);
        assert_eq!(s.generation_of(2), 1);
        s.free(1);
        assert_eq!(s.generation_of(0), 1);
        let (i, g, _) = s.alloc();
        assert_eq!((i, g), (1, 3));
        assert_eq!(s.generation_of(1), 3);
        assert_eq!(s.generation_of(0), 1);
    }

    #[test]
    fn intact_until_first_free() {
        let mut s = Slots::full(2);
        assert!(s.intact() && s.is_current(1, 1) && !s.is_current(2, 1) && !s.is_current(0, 3));
        s.free(0);
        assert!(!s.intact());
        assert!(!s.is_current(0, 1), "a freed slot's old key is stale");
        assert!(s.is_current(1, 1));
    }

    #[test]
    fn even_generation_never_current() {
        let s = Slots::from_generations(vec![1, 2, 3]);
        assert!(s.is_current(0, 1));
        assert!(!s.is_current(1, 2));
        assert_eq!(s.live(), 2);
        assert!(!s.is_current(7, 1));
    }
}
