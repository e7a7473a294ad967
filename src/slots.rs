//! Generational slot bookkeeping, shared by the three arenas.
//!
//! Why not `slotmap` (or the archived `generational-arena`)? Those crates
//! store the generation *inside* each value's slot and give every arena its
//! own key space. meshloom needs three things they do not offer together:
//! twin half-edges that share one generation (so `twin` is arithmetic and
//! costs no storage), attribute columns that sit beside the arena and are
//! indexed by the same slot number, and a free list that costs nothing while
//! no element has been removed (a freshly built mesh has none). Measured in
//! `bench_peers`: this keeps a triangle mesh with f64 positions at about 132
//! heap bytes per vertex, generations included.
//!
//! # Generations
//!
//! A slot's generation is odd while it is occupied and even while it is
//! vacant, so a live key always has an odd generation and a scan over
//! `generations` alone tells which slots are live. Freeing a slot and
//! reusing it each add one, so a key kept across a removal no longer
//! matches. Generations only grow and never wrap: a slot whose next
//! generation would pass [`MAX_LIVE_GENERATION`] is retired (left vacant,
//! never reused) instead of wrapping round to an old key. The decisions are
//! compares or checked arithmetic (`reusable`, [`Slots::compacted`],
//! [`Slots::from_generations`]); the increments in `alloc` and `free` then
//! have room by construction (asserted in debug builds).
//!
//! Every arena has a **base** generation (odd, 1 for a built mesh): a new
//! slot at the end starts at the base, and every generation in the arena is
//! at least the base. [`Mesh::compact`](crate::Mesh::compact) moves elements
//! to other slots, so it gives every element a base above every generation
//! the arena ever issued ([`Slots::compacted`]): every key from before is
//! then stale, and only the returned maps give the new ones.
//!
//! # Fast paths
//!
//! While every live generation equals the base (`pristine`: no slot reused
//! since the arena was built or compacted), making a key for a neighbour
//! needs no load from `generations`, which cuts a fifth off one-ring
//! circulation on a freshly built mesh (2.5 ms to 2.0 ms on the 250k-vertex
//! grid).
//!
//! Likewise, while no slot was freed since then (`intact`), every slot is
//! live at the base, so checking a key is a compare with the base and a
//! bounds test, with no load: reading an attribute by key on a mesh that was
//! loaded and not edited costs what indexing a `Vec` costs. Both paths
//! survive compaction, which leaves every arena pristine and intact at its
//! new base.

/// The largest generation a live slot gets. Freeing it gives the even
/// `MAX_LIVE_GENERATION + 1`, which is never reissued.
pub(crate) const MAX_LIVE_GENERATION: u32 = u32::MAX - 2;

/// Generations and the free list of one arena.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Slots {
    generations: Vec<u32>,
    free: Vec<u32>,
    live: usize,
    /// Odd; a new slot starts here, and no slot's generation is below it.
    base: u32,
    /// How much is known without reading `generations` (one field, so that
    /// "intact implies pristine" is visible to the optimizer: a key made
    /// and checked in one loop compares the base with itself).
    state: State,
}

/// What every slot is known to be.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum State {
    /// No slot freed since the arena was built or compacted: every slot is
    /// live at the base generation, so checking a key needs no load.
    Intact,
    /// No slot reused since then: every live slot has the base generation,
    /// so making a key needs no load.
    Pristine,
    /// Generations must be read.
    Mixed,
}

impl Default for Slots {
    fn default() -> Self {
        Slots::with_capacity(0)
    }
}

impl Slots {
    /// The base of a built arena.
    pub(crate) const FIRST_BASE: u32 = 1;

    /// Slots with room for `n` elements reserved.
    pub(crate) fn with_capacity(n: usize) -> Self {
        Slots {
            generations: Vec::with_capacity(n),
            free: Vec::new(),
            live: 0,
            base: Self::FIRST_BASE,
            state: State::Intact,
        }
    }

    /// `n` live slots of generation 1, none vacant (a freshly built arena).
    pub(crate) fn full(n: usize) -> Self {
        Self::full_at(n, Self::FIRST_BASE)
    }

    /// `n` live slots at base generation `base` (odd), none vacant.
    fn full_at(n: usize, base: u32) -> Self {
        debug_assert!(base & 1 == 1 && base <= MAX_LIVE_GENERATION);
        Slots {
            generations: vec![base; n],
            free: Vec::new(),
            live: n,
            base,
            state: State::Intact,
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

    /// The base generation: every generation in the arena is at least this.
    #[inline]
    pub(crate) fn base(&self) -> u32 {
        self.base
    }

    /// The generation of slot `i`; `None` past the end.
    #[inline]
    pub(crate) fn generation(&self, i: usize) -> Option<u32> {
        self.generations.get(i).copied()
    }

    /// The current generation of a slot known to be live.
    #[inline]
    pub(crate) fn generation_of(&self, i: u32) -> u32 {
        if self.pristine() {
            self.base
        } else {
            self.generations[i as usize]
        }
    }

    /// Whether `(index, generation)` names the live element in its slot.
    #[inline]
    pub(crate) fn is_current(&self, index: u32, generation: u32) -> bool {
        if self.state == State::Intact {
            generation == self.base && (index as usize) < self.generations.len()
        } else {
            generation & 1 == 1 && self.generations.get(index as usize) == Some(&generation)
        }
    }

    /// Whether no slot was freed since the arena was built or compacted
    /// (every slot live at the base generation).
    #[inline]
    pub(crate) fn intact(&self) -> bool {
        self.state == State::Intact
    }

    /// Whether no slot was reused since the arena was built or compacted
    /// (every live slot at the base generation).
    #[inline]
    fn pristine(&self) -> bool {
        self.state <= State::Pristine
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

    /// Take a slot: a vacant one if any, else a new one at the end (at the
    /// base generation). Returns `(index, generation, is_new)`.
    #[inline]
    pub(crate) fn alloc(&mut self) -> (u32, u32, bool) {
        self.live += 1;
        if let Some(i) = self.free.pop() {
            self.state = State::Mixed;
            let g = &mut self.generations[i as usize];
            // The free list holds only slots whose next generation exists
            // (`reusable`, checked when the slot was freed): no overflow.
            *g += 1;
            debug_assert!(*g & 1 == 1 && *g <= MAX_LIVE_GENERATION);
            (i, *g, false)
        } else {
            let i = u32::try_from(self.generations.len()).expect("more than 2^32 slots");
            self.generations.push(self.base);
            (i, self.base, true)
        }
    }

    /// Vacate slot `i`. Keys to it become stale. A slot whose next
    /// generation would pass [`MAX_LIVE_GENERATION`] is retired instead of
    /// reused, so no key is ever reissued.
    pub(crate) fn free(&mut self, i: u32) {
        let g = &mut self.generations[i as usize];
        debug_assert!(*g & 1 == 1, "freeing a vacant slot");
        if self.state == State::Intact {
            self.state = State::Pristine;
        }
        // A live generation is at most MAX_LIVE_GENERATION (issued only
        // through `reusable` or a checked base): no overflow.
        debug_assert!(*g <= MAX_LIVE_GENERATION);
        *g += 1;
        self.live -= 1;
        if Self::reusable(*g) {
            self.free.push(i);
        }
    }

    /// Whether a vacant slot of (even) generation `g` may be issued again:
    /// whether `g + 1` is at most [`MAX_LIVE_GENERATION`] (a compare, so
    /// nothing can overflow).
    #[inline]
    fn reusable(g: u32) -> bool {
        g < MAX_LIVE_GENERATION
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

    /// The arena after compaction into `live` dense slots: every slot live
    /// at a new base above every generation this arena ever issued (the
    /// largest in `generations`, or below the old base for slots an earlier
    /// compaction dropped), so every earlier key is stale. `None` when that
    /// base would pass [`MAX_LIVE_GENERATION`]: the arena cannot be
    /// compacted without reissuing a generation.
    pub(crate) fn compacted(&self, live: usize) -> Option<Slots> {
        let highest = self.generations.iter().copied().max().unwrap_or(0);
        let above = highest.max(self.base).checked_add(1)? | 1;
        (above <= MAX_LIVE_GENERATION).then(|| Slots::full_at(live, above))
    }

    /// Rebuild from raw generations and the base (deserialization), refusing
    /// what meshloom never issues: a base that is even or past
    /// [`MAX_LIVE_GENERATION`], a live generation past it, or a generation
    /// below the base. Vacant slots are the even ones; those with a next
    /// generation go on the free list, the others stay retired.
    #[cfg(any(feature = "serde", test))]
    pub(crate) fn from_generations(generations: Vec<u32>, base: u32) -> Result<Self, String> {
        if base & 1 == 0 || base > MAX_LIVE_GENERATION {
            return Err(format!(
                "base generation {base} is not an odd number up to {MAX_LIVE_GENERATION}"
            ));
        }
        if let Some((i, g)) = generations
            .iter()
            .enumerate()
            .find(|(_, &g)| g < base || (g & 1 == 1 && g > MAX_LIVE_GENERATION))
        {
            return Err(if *g < base {
                format!("slot {i} has generation {g}, below the base generation {base}")
            } else {
                format!(
                    "slot {i} has the live generation {g}, past the largest meshloom issues ({MAX_LIVE_GENERATION})"
                )
            });
        }
        let free: Vec<u32> = generations
            .iter()
            .enumerate()
            .filter(|(_, g)| *g & 1 == 0 && Self::reusable(**g))
            .map(|(i, _)| i as u32)
            .rev()
            .collect();
        let live = generations.iter().filter(|g| *g & 1 == 1).count();
        let state = if generations.iter().all(|&g| g == base) {
            State::Intact
        } else if generations.iter().all(|&g| g & 1 == 0 || g == base) {
            State::Pristine
        } else {
            State::Mixed
        };
        Ok(Slots {
            generations,
            free,
            live,
            base,
            state,
        })
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
        let s = Slots::from_generations(vec![1, 2, 3], 1).unwrap();
        assert!(s.is_current(0, 1));
        assert!(!s.is_current(1, 2));
        assert_eq!(s.live(), 2);
        assert!(!s.is_current(7, 1));
    }

    #[test]
    fn compaction_raises_the_base_above_every_generation() {
        let mut s = Slots::full(3);
        s.free(1);
        let (i, g, _) = s.alloc(); // slot 1 again, generation 3
        assert_eq!((i, g), (1, 3));
        s.free(2); // generation 2: vacant
        let c = s.compacted(2).unwrap();
        assert_eq!(c.base(), 5);
        assert_eq!(c.generations(), [5, 5]);
        assert!(c.intact() && c.pristine());
        for (i, g) in [(0, 1), (1, 3), (1, 1), (2, 1)] {
            assert!(!c.is_current(i, g), "({i}, {g})");
        }
        assert!(c.is_current(1, 5));
        // A new slot starts at the base, above every key issued before.
        let mut c = c;
        assert_eq!(c.alloc(), (2, 5, true));
    }

    #[test]
    fn generations_never_wrap() {
        let top = MAX_LIVE_GENERATION;
        let mut s = Slots::from_generations(vec![top, top - 2], 1).unwrap();
        assert!(!s.pristine() && !s.intact());
        s.free(0); // top + 1: retired
        s.free(1); // top - 1: its next generation is top, still reusable
        let (i, g, new) = s.alloc();
        assert_eq!((i, g, new), (1, top, false));
        // Slot 0 is never reissued; a new slot comes at the end.
        let (i, g, new) = s.alloc();
        assert_eq!((i, g, new), (2, 1, true));
        assert!(!s.is_current(0, top));
        // Compaction cannot raise the base past the largest live generation.
        assert!(s.compacted(2).is_none());
    }

    #[test]
    fn impossible_generations_are_refused() {
        assert!(Slots::from_generations(vec![u32::MAX], 1).is_err());
        assert!(Slots::from_generations(vec![1, 3], 3).is_err());
        assert!(Slots::from_generations(vec![5], 4).is_err());
        assert!(Slots::from_generations(vec![u32::MAX], u32::MAX).is_err());
        let s = Slots::from_generations(vec![u32::MAX - 1, 7], 7).unwrap();
        assert_eq!(s.live(), 1);
        assert!(
            s.free.is_empty(),
            "a vacant slot at u32::MAX - 1 is retired"
        );
    }
}
