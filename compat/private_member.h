// private_member.h — reading a Bullet member that has no getter (btHingeConstraint's limit
// centre, btRigidBody's additional damping): a member pointer named in an explicit
// instantiation, where C++ does not check access. Read only; nothing is written through it.
#pragma once

namespace btgpu {

template <class Tag, typename Tag::type Member>
struct PrivateMemberReader {
    friend typename Tag::type member(Tag) { return Member; }
};

}  // namespace btgpu

// Declares tag Name for Class::Field of type Type; `obj.*member(Name())` then reads it.
#define BTGPU_PRIVATE_MEMBER(Name, Class, Type, Field) \
    struct Name {                                      \
        using type = Type Class::*;                    \
        friend type member(Name);                      \
    };                                                 \
    template struct PrivateMemberReader<Name, &Class::Field>
