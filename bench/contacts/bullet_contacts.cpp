#include "contacts/bullet_contacts.hpp"

#include <btBulletCollisionCommon.h>

#include <cstdint>

namespace softstep::bench {

struct BulletContacts::Impl {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btCollisionWorld world{&dispatcher, &broadphase, &configuration};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btCollisionObject>> objects;
  std::vector<BodyId> bodies;  // per object, its user index
  std::vector<ContactManifold> manifolds;
  std::uintptr_t next_feature = 1;

  void add(BodyId body, std::unique_ptr<btCollisionShape> shape) {
    auto object = std::make_unique<btCollisionObject>();
    object->setCollisionShape(shape.get());
    object->setUserIndex(static_cast<int>(bodies.size()));
    bodies.push_back(body);
    world.addCollisionObject(object.get());
    shapes.push_back(std::move(shape));
    objects.push_back(std::move(object));
  }
};

BulletContacts::BulletContacts() : impl_(std::make_unique<Impl>()) {}
BulletContacts::~BulletContacts() {
  for (auto& o : impl_->objects) impl_->world.removeCollisionObject(o.get());
}

void BulletContacts::add_box(BodyId body, const Eigen::Vector3d& half) {
  impl_->add(body, std::make_unique<btBoxShape>(btVector3(btScalar(half.x()), btScalar(half.y()),
                                                          btScalar(half.z()))));
}

void BulletContacts::add_sphere(BodyId body, double radius) {
  impl_->add(body, std::make_unique<btSphereShape>(btScalar(radius)));
}

const std::vector<ContactManifold>& BulletContacts::find(const World& world, double friction,
                                                         double restitution) {
  Impl& b = *impl_;
  for (std::size_t i = 0; i < b.objects.size(); ++i) {
    const BodyState s = world.body(b.bodies[i]);
    btTransform t;
    t.setOrigin(btVector3(btScalar(s.position.x()), btScalar(s.position.y()),
                          btScalar(s.position.z())));
    t.setRotation(btQuaternion(btScalar(s.orientation.x()), btScalar(s.orientation.y()),
                               btScalar(s.orientation.z()), btScalar(s.orientation.w())));
    b.objects[i]->setWorldTransform(t);
  }
  b.world.performDiscreteCollisionDetection();
  b.manifolds.clear();
  const int count = b.dispatcher.getNumManifolds();
  for (int i = 0; i < count; ++i) {
    btPersistentManifold* pm = b.dispatcher.getManifoldByIndexInternal(i);
    const int points = std::min(pm->getNumContacts(), kMaxContactPoints);
    if (points == 0) continue;
    ContactManifold m;
    m.body_a = b.bodies[static_cast<std::size_t>(pm->getBody0()->getUserIndex())];
    m.body_b = b.bodies[static_cast<std::size_t>(pm->getBody1()->getUserIndex())];
    m.friction = friction;
    m.restitution = restitution;
    // Bullet's normal is on B pointing towards A; softstep's goes from A to B.
    const btVector3 n = -pm->getContactPoint(0).m_normalWorldOnB;
    m.normal = Eigen::Vector3d(n.x(), n.y(), n.z()).normalized();
    m.point_count = points;
    for (int k = 0; k < points; ++k) {
      btManifoldPoint& p = pm->getContactPoint(k);
      // Bullet keeps a manifold's points from step to step while they persist: the id given
      // to a point when first seen is its feature id for warm starting.
      if (p.m_userPersistentData == nullptr) {
        p.m_userPersistentData = reinterpret_cast<void*>(b.next_feature++);
      }
      ContactPoint& c = m.points[static_cast<std::size_t>(k)];
      c.anchor_a = {p.m_localPointA.x(), p.m_localPointA.y(), p.m_localPointA.z()};
      c.anchor_b = {p.m_localPointB.x(), p.m_localPointB.y(), p.m_localPointB.z()};
      c.separation = p.getDistance();
      c.feature_id = static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(p.m_userPersistentData));
    }
    b.manifolds.push_back(m);
  }
  return b.manifolds;
}

}  // namespace softstep::bench
